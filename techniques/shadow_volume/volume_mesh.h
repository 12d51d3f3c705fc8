#pragma once
// A caster's shadow volume as triangles, from its silhouette (silhouette.h),
// in homogeneous coordinates: w = 1 on the caster, w = 0 for a point pushed
// to infinity away from the light (drawn under GL_DEPTH_CLAMP).
//
// The volume is closed, with every face wound outwards:
//   sides  each loop edge a → b (smooth positions) extruded: (a, a∞, b), (b, a∞, b∞);
//   strip  where the smooth loop leaves the mesh, the band from each loop
//          edge's mesh positions to its smooth ones, so the near cap (on the
//          mesh) meets the sides without a gap;
//   caps   near: the lit region on the mesh; far: the lit region and the
//          strip at infinity, reversed.
// z-pass draws the sides and the strip (the strip may lie in front of a
// visible surface, the near cap never does); z-fail draws everything.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "shadow_volume/silhouette.h"

namespace sb::techniques::shadow_volume {

struct VolumeVertices {
  std::vector<glm::vec4> vertices;  // triangle list
  // One caster's triangles: [first, first + sides) the sides and strip,
  // then `caps` vertices of caps (0 without caps).
  struct Range {
    int32_t first = 0;
    int32_t sides = 0;
    int32_t caps = 0;
  };
  void clear() { vertices.clear(); }
};

// Appends one caster's volume and returns where it lies.
VolumeVertices::Range append_volume(const Silhouette& silhouette, const glm::vec3& light, bool caps,
                                    VolumeVertices& out);

}  // namespace sb::techniques::shadow_volume
