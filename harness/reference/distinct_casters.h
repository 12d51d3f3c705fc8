#pragma once
// A scene's casters without repeats (internal to the reference). A caster
// that repeats an earlier one exactly (the same triangles at the same place,
// the same mask and shape) hides exactly the same light: the union of the
// casters, which is all V depends on, is unchanged without it. A glTF whose
// nodes place one mesh many times at one spot (issue 65's 200,000 instances)
// would otherwise give Embree and the exact reference's hierarchy thousands
// of boxes they cannot tell apart, and every ray or light pyramid through
// them would test each copy.
#include <optional>

#include "core/scene.h"

namespace sb::reference::detail {

// The scene with every caster that repeats an earlier caster left out (its
// receivers and everything else kept, in order); nullopt when none repeats.
std::optional<core::Scene> without_repeated_casters(const core::Scene& scene);

}  // namespace sb::reference::detail
