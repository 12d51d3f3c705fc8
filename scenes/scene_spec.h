#pragma once
// A scene named on the command line, as `sphere_grid:grid=3,light_size=2` or
// as a JSON object `{"type": "sphere_grid", "params": {"grid": 3}}`.
// Path parameters are relative to the working directory.
#include <string>

#include "core/scene.h"

namespace sb {

// Throws InputError (file "scene spec") naming the bad parameter.
core::Scene build_scene_from_spec(const std::string& spec);

// Meshes, triangles, textures, bounds, light and camera; closedness per mesh.
std::string describe_scene(const core::Scene& scene);

}  // namespace sb
