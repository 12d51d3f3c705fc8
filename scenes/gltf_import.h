#pragma once
// glTF 2.0 (.gltf and .glb) as a scene: the default scene's meshes flattened
// to world space, base colour, base colour textures and alpha masks, the first
// perspective camera and the first KHR_lights_punctual light. What is read and
// what is refused is listed in docs/scenes.md.
#include <string>

#include "core/scene.h"

namespace sb {

struct GltfImportOptions {
  // Side of the square area light; <= 0 takes the size the file stores
  // (extras written by export_glb) or else 5% of the scene's diagonal.
  float light_size = 0.0f;
  // Uniform scale of everything: geometry, light, camera.
  float scale = 1.0f;
};

// Malformed or unsupported input throws InputError naming the file and the
// place ("accessor 3", "node 'wheel' (5)", "image 2 uri", ...); it never reads
// files outside the glTF file's own folder.
core::Scene load_gltf(const std::string& path, const GltfImportOptions& options = {});

// Limits, checked before anything of that size is allocated.
inline constexpr size_t kGltfMaxTriangles = 100'000'000;  // whole scene, after instancing
inline constexpr size_t kGltfMaxElements = 300'000'000;   // per accessor
inline constexpr int kGltfMaxTextureSide = 16384;         // texels
// All decoded textures of one file together (one 8192² texture; 256 MiB as RGBA8).
inline constexpr size_t kGltfMaxDecodedTexels = size_t(1) << 26;

}  // namespace sb
