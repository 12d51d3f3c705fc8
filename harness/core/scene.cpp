#include "core/scene.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace sb {

float sample_alpha(const TextureImage& texture, glm::vec2 uv) {
  if (texture.width <= 0 || texture.height <= 0) return 1.0f;
  const auto wrap = [](float t, int size) {
    const auto i = static_cast<long long>(std::floor(double(t) * size));
    return static_cast<size_t>(((i % size) + size) % size);
  };
  const size_t x = wrap(uv.x, texture.width), y = wrap(uv.y, texture.height);
  return float(texture.rgba[(y * size_t(texture.width) + x) * 4 + 3]) / 255.0f;
}

glm::mat4 Camera::view() const { return glm::lookAt(eye, target, up); }

glm::mat4 Camera::projection(float aspect) const {
  return glm::perspective(glm::radians(fov_y_degrees), aspect, near_plane, far_plane);
}

size_t Scene::triangle_count() const {
  size_t n = 0;
  for (const auto& m : meshes) n += m.triangle_count();
  return n;
}

size_t Scene::caster_triangle_count() const {
  size_t n = 0;
  for (const auto& m : meshes)
    if (m.casts_shadow) n += m.triangle_count();
  return n;
}

// Only vertices a triangle references count: glTF primitives may share one
// POSITION accessor and each index a subset of it.
Bounds Scene::bounds() const {
  Bounds b;
  for (const auto& m : meshes)
    for (const uint32_t i : m.indices) b.extend(m.positions.at(i));
  return b;
}

Bounds Scene::caster_bounds() const {
  Bounds b;
  for (const auto& m : meshes)
    if (m.casts_shadow)
      for (const uint32_t i : m.indices) b.extend(m.positions.at(i));
  return b;
}

}  // namespace sb
