#pragma once
#include <string>
#include <vector>

#include "core/scene_types.h"

namespace sb {
// The jeep scene of Atty et al. 2006 and Eisemann & Décoret 2008: N
// procedural jeeps over a ground plane under a square area light, to show how
// shadow cost scales with geometry. Parameters are documented in jeep.cpp.
core::SceneType jeep_scene_type();

// One jeep in its own frame: on the ground plane y = 0, facing +z, its left
// side towards +x, wheelbase centred on the origin. Every part is a closed
// caster mesh named `prefix` + "/" + part; round parts use `tessellation`
// segments (tubes and tyre cross-sections half as many).
std::vector<core::Mesh> make_jeep(const std::string& prefix, int tessellation);
}  // namespace sb
