#pragma once
#include "core/scene_types.h"

namespace sb {
// Stiff cases for soft-shadow filters: thin closed plates over a ground plane
// under a square area light facing straight down. "edge": one plate whose
// straight edge casts a straight penumbra (PCSS width against light size);
// "stacked": an upper plate whose edge lies over a lower, larger plate, the
// configuration in which variance shadow maps bleed light into the lower
// plate's umbra (Lauritzen, GPU Gems 3 ch. 8). Parameters and placement are
// documented in plates.cpp.
core::SceneType plates_scene_type();
}  // namespace sb
