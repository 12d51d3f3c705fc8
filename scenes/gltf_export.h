#pragma once
// A Scene as binary glTF 2.0 (.glb): one node and mesh per sb::Mesh (world
// space, named), materials with embedded PNG textures, the camera, and the
// area light as a KHR_lights_punctual spot light whose extras keep the
// rectangle's size so load_gltf restores it (docs/scenes.md lists the extras).
#include <cstdint>
#include <string>
#include <vector>

#include "core/scene.h"

namespace sb {

std::vector<uint8_t> export_glb_bytes(const core::Scene& scene);
// Writes atomically (core/atomic_file.h); throws JobError (a
// std::runtime_error) when the file cannot be written.
void export_glb(const core::Scene& scene, const std::string& path);

}  // namespace sb
