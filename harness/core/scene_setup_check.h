#pragma once
// Setups that would render "ok" with a meaningless error column: a camera
// that sees nothing (eye on its target, up along the view, a field of view
// that rounds to zero, near not before far), non-finite or astronomically
// large coordinates (a node scale of 1e30), or geometry with no triangle of
// non-zero area. Checked on the built scene, after a config's overrides, so a
// glTF's own camera and transforms are covered too.
#include <string>

#include "core/scene.h"

namespace sb::core {

// Coordinates beyond this cannot be ray traced (Embree's 1.8e18, with room
// for the offsets and light directions made from them).
constexpr float kLargestCoordinate = 1e15f;

// "" when the scene can be measured, else what is wrong, naming the part
// ("camera: eye equals target (0, 1, 2)").
std::string scene_setup_problem(const Scene& scene);

// The camera alone (the config checks its overrides with it).
std::string camera_problem(const Camera& camera);

}  // namespace sb::core
