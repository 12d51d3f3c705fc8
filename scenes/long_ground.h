#pragma once
#include "core/scene_types.h"

namespace sb {
// A long strip of ground lined with posts, seen by a camera near the ground
// looking along it: a depth range of hundreds to one, where a uniform shadow
// map's texels are too coarse near the camera and wasted far away
// (perspective aliasing). Parameters and placement are documented in
// long_ground.cpp.
core::SceneType long_ground_scene_type();
}  // namespace sb
