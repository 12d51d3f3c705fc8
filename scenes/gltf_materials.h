#pragma once
// glTF materials as the benchmark uses them: the base colour factor and
// texture (KHR_texture_transform kept as a matrix for the UVs), double-sidedness,
// and alpha: MASK keeps its cutoff and BLEND becomes a mask at 0.5 (nothing
// is blended here), so the camera, the depth passes and the reference all
// test the same texel (sample_alpha in core/scene.h). Images shared by
// several textures or materials become one Scene texture.
#include <map>
#include <vector>

#include "core/scene.h"
#include "scenes/gltf_common.h"
#include "scenes/gltf_images.h"

namespace sb::gltf {

struct MaterialInfo {
  glm::vec3 albedo{1.0f};
  int texture = -1;  // into the Scene's textures
  int texcoord = 0;
  core::AlphaMode mode = core::AlphaMode::Opaque;
  float cutoff = 0.5f;
  bool double_sided = false;
  bool transform = false;
  glm::dmat3 uv_transform{1.0};  // column-major: uv' = M * (u, v, 1)
};

class MaterialReader : public ImportStep {
 public:
  // Decoded textures are appended to `textures`.
  MaterialReader(const std::string& file, const tg::Model& model,
                 std::vector<core::TextureImage>& textures)
      : ImportStep(file), model_(model), textures_(textures), images_(file) {}
  // Material `index` (< 0: glTF's default material) of the primitive named `primitive`.
  MaterialInfo material(int index, const std::string& primitive);

 private:
  int texture_for(int texture_index, const std::string& where);
  void texture_transform(const tg::Value& t, const std::string& where, MaterialInfo& info) const;

  const tg::Model& model_;
  std::vector<core::TextureImage>& textures_;
  ImageDecoder images_;
  std::map<int, int> image_to_texture_;
};

}  // namespace sb::gltf
