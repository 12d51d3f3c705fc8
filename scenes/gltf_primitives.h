#pragma once
// A glTF mesh's primitives as triangle lists. Triangles, strips and fans are
// read (points and lines are refused); the triangle count is checked against
// the limit before anything large is read; positions, normals and the UV set
// the material names come through the bounds-checked accessors, the
// material's texture transform baked into the UVs. Each mesh is loaded once
// and shared by every node that instances it.
#include <map>
#include <vector>

#include "core/scene.h"
#include "scenes/gltf_accessors.h"
#include "scenes/gltf_common.h"
#include "scenes/gltf_materials.h"

namespace sb::gltf {

struct LoadedPrimitive {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // empty: flat normals are generated per instance
  std::vector<glm::vec2> uvs;
  std::vector<uint32_t> indices;  // triangle list
  glm::vec3 albedo{1.0f};
  int texture = -1;
  core::AlphaMode alpha_mode = core::AlphaMode::Opaque;
  float alpha_cutoff = 0.5f;
  bool double_sided = false;
};

class PrimitiveLoader : public ImportStep {
 public:
  // Textures the materials use are appended to `textures`.
  PrimitiveLoader(const std::string& file, const tg::Model& model,
                  std::vector<core::TextureImage>& textures)
      : ImportStep(file),
        model_(model),
        accessors_(file, model),
        materials_(file, model, textures) {}
  // The primitives of mesh `mesh_index` (which must exist), loaded on first use.
  const std::vector<LoadedPrimitive>& mesh_primitives(size_t mesh_index);

 private:
  LoadedPrimitive load_primitive(size_t mesh_index, size_t prim_index);

  const tg::Model& model_;
  AccessorReader accessors_;
  MaterialReader materials_;
  std::map<size_t, std::vector<LoadedPrimitive>> loaded_;
};

}  // namespace sb::gltf
