#pragma once
#include "core/scene_types.h"

namespace sb {
// A glTF 2.0 file (.gltf or .glb) as a scene; see docs/scenes.md.
core::SceneType gltf_scene_type();
}  // namespace sb
