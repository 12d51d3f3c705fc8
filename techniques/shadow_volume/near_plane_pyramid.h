#pragma once
// `mode: auto`: z-fail only for the casters whose shadow volume can reach the
// camera's near-plane rectangle, z-pass for the rest. A volume contains a
// point q of that rectangle exactly when the caster cuts the segment from the
// light to q, so it can only when the caster meets the pyramid spanned by the
// light and the rectangle. The test is conservative (an axis-aligned box
// against the pyramid's planes): it may send a caster to z-fail that did not
// need it, which costs time but never correctness.
#include <array>
#include <glm/glm.hpp>

#include "core/scene.h"

namespace sb::techniques::shadow_volume {

class NearPlanePyramid {
 public:
  // The rectangle is where the camera's near plane meets its frustum.
  NearPlanePyramid(const glm::vec3& light, const glm::mat4& view_projection);
  // False only when the box lies wholly outside the pyramid.
  bool may_intersect(const core::Bounds& box) const;

 private:
  std::array<glm::vec4, 6> planes_{};  // n·x + d > 0 outside
  bool degenerate_ = false;            // the light on the near plane: assume it may
};

}  // namespace sb::techniques::shadow_volume
