#pragma once
// How far the reference's shadow rays start off the surface (internal).
//
// A ray from a point p on a caster can hit that caster's own triangle at
// t ≈ 0 unless its origin sits clearly on the lit side. "Clearly" is a matter
// of float rounding, which grows with the size of the coordinates involved:
// p's own (and the G-buffer rounded p when it interpolated the triangle), and
// the triangle's vertices (Embree's hit test works on vertex − origin
// differences). So the origin moves along the normal by
//   eps = kOffsetRelative · max(max_i |p_i|, M),
// M the largest |coordinate| of the caster triangles p lies on, within that
// same rounding (an Embree point query; 0 on receivers, which no ray can
// hit). Nothing farther away enters: a huge ground does not blur the contact
// shadow of a small object elsewhere on it (it did with an offset scaled by
// the whole scene's radius), though points on a huge caster get the offset
// that caster's coordinates need. Analytic shapes (Mesh::analytic) add
// nothing to M: the own mesh's shape never occludes its points (reference.h),
// and other meshes' shapes only touch them where two casters touch.
#include <embree3/rtcore.h>

#include <glm/vec3.hpp>

#include "core/scene.h"
#include "reference/embree_scene.h"

namespace sb::reference::detail {

// 2^-16: 128 ulps of a coordinate (float spacing is 2^-23 relative). On
// rasterised G-buffers of the shipped scenes acne appears at 2^-20.
constexpr float kOffsetRelative = 0x1p-16f;

class RayOffset {
 public:
  // `casters` is the scene the shadow rays are traced in (may be empty).
  RayOffset(const Scene& scene, const FlatScene& casters) : scene_(scene), casters_(casters) {}
  // eps for a surface point p; thread-safe.
  float at(const glm::vec3& p) const;

 private:
  const Scene& scene_;
  const FlatScene& casters_;
};

}  // namespace sb::reference::detail
