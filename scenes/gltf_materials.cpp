#include "scenes/gltf_materials.h"

#include <algorithm>
#include <cmath>

namespace sb::gltf {

using core::AlphaMode;

MaterialInfo MaterialReader::material(int index, const std::string& primitive) {
  MaterialInfo info;  // glTF's default material: white, opaque
  if (index < 0) return info;
  if (size_t(index) >= model_.materials.size())
    fail(primitive, "material " + std::to_string(index) + " does not exist (" +
                        str(model_.materials.size()) + " materials)");
  const tg::Material& m = model_.materials[size_t(index)];
  const std::string where = named("material", m.name, size_t(index));
  const auto& f = m.pbrMetallicRoughness.baseColorFactor;
  if (f.size() != 4) fail(where, "baseColorFactor: expected 4 numbers");
  for (int c = 0; c < 3; ++c) {
    if (!std::isfinite(f[size_t(c)])) fail(where, "baseColorFactor is not finite");
    info.albedo[c] = static_cast<float>(std::clamp(f[size_t(c)], 0.0, 1.0));
  }
  if (m.alphaMode == "MASK") {
    if (!std::isfinite(m.alphaCutoff) || m.alphaCutoff < 0)
      fail(where, "alphaCutoff must be a non-negative number");
    info.mode = AlphaMode::Mask;
    info.cutoff = static_cast<float>(m.alphaCutoff);
  } else if (m.alphaMode == "BLEND") {
    info.mode = AlphaMode::Mask;  // no blending in the benchmark: coverage at 0.5
    info.cutoff = 0.5f;
  } else if (m.alphaMode != "OPAQUE") {
    fail(where, "alphaMode " + quoted(m.alphaMode) + " is not OPAQUE, MASK or BLEND");
  }
  info.double_sided = m.doubleSided;
  const tg::TextureInfo& tex = m.pbrMetallicRoughness.baseColorTexture;
  if (tex.index >= 0) {
    info.texture = texture_for(tex.index, where);
    info.texcoord = tex.texCoord;
    const auto ext = tex.extensions.find("KHR_texture_transform");
    if (ext != tex.extensions.end()) texture_transform(ext->second, where, info);
  }
  if (info.texcoord < 0 || info.texcoord > 7)
    fail(where, "baseColorTexture.texCoord " + std::to_string(info.texcoord) + " is invalid");
  return info;
}

int MaterialReader::texture_for(int texture_index, const std::string& where) {
  if (texture_index < 0 || size_t(texture_index) >= model_.textures.size())
    fail(where, "baseColorTexture: texture " + std::to_string(texture_index) + " does not exist (" +
                    str(model_.textures.size()) + " textures)");
  const tg::Texture& t = model_.textures[size_t(texture_index)];
  const std::string twhere = named("texture", t.name, size_t(texture_index));
  if (t.source < 0)
    fail(twhere,
         "has no PNG or JPEG source image (EXT_texture_webp and KHR_texture_basisu "
         "are not supported)");
  if (size_t(t.source) >= model_.images.size())
    fail(twhere, "source image " + std::to_string(t.source) + " does not exist (" +
                     str(model_.images.size()) + " images)");
  // Images shared by textures and materials become one Scene texture.
  const auto found = image_to_texture_.find(t.source);
  if (found != image_to_texture_.end()) return found->second;
  textures_.push_back(images_.decode(model_.images[size_t(t.source)], size_t(t.source)));
  const int sb_index = int(textures_.size() - 1);
  image_to_texture_[t.source] = sb_index;
  return sb_index;
}

// KHR_texture_transform is baked into the UVs (one material per Mesh here).
void MaterialReader::texture_transform(const tg::Value& t, const std::string& where,
                                       MaterialInfo& info) const {
  const std::string w = where + " KHR_texture_transform";
  const auto pair = [&](const char* key, glm::dvec2 def) {
    const tg::Value* v = member(t, key);
    if (v == nullptr) return def;
    double a = 0, b = 0;
    if (!v->IsArray() || v->ArrayLen() != 2 || !finite_number(&v->Get(0), a) ||
        !finite_number(&v->Get(1), b))
      fail(w, std::string(key) + ": expected 2 numbers");
    return glm::dvec2(a, b);
  };
  const glm::dvec2 offset = pair("offset", glm::dvec2(0.0));
  const glm::dvec2 scale = pair("scale", glm::dvec2(1.0));
  double rotation = 0;
  if (member(t, "rotation") != nullptr && !finite_number(member(t, "rotation"), rotation))
    fail(w, "rotation: expected a number");
  if (const tg::Value* tc = member(t, "texCoord")) {
    if (!tc->IsInt()) fail(w, "texCoord: expected an integer");
    info.texcoord = tc->Get<int>();
  }
  const double c = std::cos(rotation), s = std::sin(rotation);
  // T * R * S from the extension's spec, written column by column.
  info.uv_transform =
      glm::dmat3(glm::dvec3(c * scale.x, -s * scale.x, 0), glm::dvec3(s * scale.y, c * scale.y, 0),
                 glm::dvec3(offset.x, offset.y, 1));
  info.transform = true;
}

}  // namespace sb::gltf
