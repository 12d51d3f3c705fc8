#pragma once
// What tracing already settled about an agreeing pixel's penumbra membership
// (reference.h: Result::penumbra), so that the penumbra pass does not prove
// it again (internal).
#include <cstdint>

namespace sb::reference::detail {

enum class Settled : uint8_t {
  // Nothing: ask ExactVisibility::partly_lit (its two proofs, then V).
  Unknown,
  // A proof holds (exact_visibility.h: sees_whole_light, hides_whole_light):
  // V is exactly 1 or 0, outside the penumbra.
  Proven,
  // The one proof that could hold did not (the other contradicts the
  // pixel's samples: all lit, or all occluded): ask V itself.
  Unproven,
};

}  // namespace sb::reference::detail
