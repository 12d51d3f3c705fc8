#pragma once
// This family's own need, "receiver_basis": an orthonormal frame on the
// planar receiver and the receiver mesh's extent in it, so a texture can be
// laid over the receiver. It depends on the scene alone, never on the light,
// so computing it once per scene hides no per-frame work.
#include <glm/glm.hpp>

#include "plugin/needs.h"

namespace blurred {

inline constexpr const char* kReceiverBasis = "receiver_basis";

struct ReceiverBasis {
  glm::vec4 plane{0.0f};   // n·x + d = 0, n towards the casters
  glm::vec3 origin{0.0f};  // on the plane, the centre of the receiver's extent
  glm::vec3 u{1, 0, 0}, v{0, 0, 1};
  glm::vec2 half_extent{1.0f};  // along u and v
};

sb::plugin::NeedProvider receiver_basis_provider();

}  // namespace blurred
