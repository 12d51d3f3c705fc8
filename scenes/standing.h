#pragma once
#include "core/scene_types.h"

namespace sb {
// A box standing on the ground (a pole, or a character-sized block) under a
// square area light to one side: its shadow is hard at the contact line and
// widest at its far end, the case that fixed-width blurs cannot follow.
// Parameters and placement are documented in standing.cpp.
core::SceneType standing_scene_type();
}  // namespace sb
