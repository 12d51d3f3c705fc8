#pragma once
#include "core/scene_types.h"

namespace sb {
// A kilometre of ground under the sun, seen by a pedestrian: a road with
// street lights, buildings, trees with alpha-masked leaves, power poles and
// sign posts, from a few centimetres to tens of metres across, from the
// camera's feet to the far end. Parameters and placement are documented in
// outdoor.cpp and docs/scenes.md.
core::SceneType outdoor_scene_type();
}  // namespace sb
