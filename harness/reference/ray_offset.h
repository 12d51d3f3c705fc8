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
// same rounding (0 on receivers, which no ray can hit): the triangles whose
// bounds lie within kOffsetRelative · max_i |p_i| of p and whose plane lies
// within kOffsetRelative · (their own largest |coordinate|) of it
// (lies_on_scale() below). The Monte Carlo reference finds the candidates
// with an Embree point query, the exact one with its own hierarchy; both
// apply that one test, so both offset every point alike. Nothing farther
// away enters: a huge ground does not blur the contact
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

// The query radius around p: kOffsetRelative · max_i |p_i|.
double offset_radius(const glm::dvec3& p);

// Triangle abc's share of M at p: its largest |coordinate| when p lies on it
// up to rounding (as above, `radius` = offset_radius(p)), else 0.
double lies_on_scale(const glm::dvec3& p, double radius, const glm::dvec3& a, const glm::dvec3& b,
                     const glm::dvec3& c);

// eps from p and M: kOffsetRelative · max(max_i |p_i|, M).
double offset_from(const glm::dvec3& p, double largest);

class RayOffset {
 public:
  // `casters` is the scene the shadow rays are traced in (may be empty).
  RayOffset(const core::Scene& scene, const FlatScene& casters)
      : scene_(scene), casters_(casters) {}
  // eps for a surface point p; thread-safe.
  float at(const glm::vec3& p) const;

 private:
  const core::Scene& scene_;
  const FlatScene& casters_;
};

}  // namespace sb::reference::detail
