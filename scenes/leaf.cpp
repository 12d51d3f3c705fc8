#include "scenes/leaf.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sb {

using core::AlphaMode;
using core::Mesh;
using core::TextureImage;

TextureImage make_leaf_texture(int size, uint32_t seed) {
  TextureImage t;
  t.name = "leaf_mask";
  t.width = t.height = size;
  t.rgba.assign(size_t(size) * size_t(size) * 4, 0);
  // A little per-seed variation in the blade's width and tint.
  const float width = 0.40f + 0.04f * float(seed % 5) / 4.0f;
  const float tint = 0.05f * float((seed / 5) % 3);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float u = (float(x) + 0.5f) / float(size) - 0.5f;
      const float v = (float(y) + 0.5f) / float(size);
      bool inside = false;
      if (v >= 0.14f && v <= 0.96f) {
        const float s = (v - 0.14f) / 0.82f;  // 0 at the blade's base, 1 at its tip
        const float half =
            width * std::pow(std::sin(std::numbers::pi_v<float> * s), 0.75f) * (1.0f - 0.35f * s);
        inside = std::fabs(u) <= half;
      } else if (v >= 0.02f && v < 0.14f) {
        inside = std::fabs(u) <= 0.025f;  // the stalk
      }
      if (!inside) continue;
      uint8_t* p = &t.rgba[(size_t(y) * size_t(size) + size_t(x)) * 4];
      const bool midrib = std::fabs(u) < 0.018f;
      p[0] = uint8_t(255.0f * std::clamp(0.20f + tint + (midrib ? 0.25f : 0.0f), 0.0f, 1.0f));
      p[1] = uint8_t(255.0f * std::clamp(0.55f + 0.25f * v + (midrib ? 0.15f : 0.0f), 0.0f, 1.0f));
      p[2] = uint8_t(255.0f * std::clamp(0.12f + (midrib ? 0.15f : 0.0f), 0.0f, 1.0f));
      p[3] = 255;
    }
  return t;
}

double opaque_fraction(const TextureImage& texture, float cutoff) {
  size_t opaque = 0;
  for (size_t i = 3; i < texture.rgba.size(); i += 4)
    opaque += float(texture.rgba[i]) / 255.0f >= cutoff;
  return double(opaque) / double(texture.rgba.size() / 4);
}

Mesh make_leaf_quad(const std::string& name, glm::vec3 center, glm::vec3 half_u, glm::vec3 half_v,
                    int texture) {
  Mesh m;
  m.name = name;
  m.positions = {center - half_u - half_v, center + half_u - half_v, center + half_u + half_v,
                 center - half_u + half_v};
  const glm::vec3 n = glm::normalize(glm::cross(half_u, half_v));
  m.normals.assign(4, n);
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.albedo = glm::vec3(1.0f);  // the texture carries the colour
  m.base_color_texture = texture;
  m.alpha_mode = AlphaMode::Mask;
  m.alpha_cutoff = 0.5f;
  m.double_sided = true;
  return m;
}

}  // namespace sb
