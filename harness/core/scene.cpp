#include "core/scene.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace sb::core {

int sun_side(const AreaLight& sun, const glm::dvec3& n) {
  // Over the disk's directions a + t·q (|q| <= 1, q ⊥ a), n·d ranges over
  // n·a ± t·|n − (n·a)·a|.
  const glm::dvec3 a = glm::normalize(glm::dvec3(sun.to_sun()));
  const double along = glm::dot(n, a);
  const double spread = std::tan(0.5 * double(sun.angular_diameter)) * glm::length(n - along * a);
  return along > spread ? 1 : along < -spread ? -1 : 0;
}

float sample_alpha(const TextureImage& texture, glm::vec2 uv) {
  if (texture.width <= 0 || texture.height <= 0) return 1.0f;
  const auto wrap = [](float t, int size) {
    const auto i = static_cast<long long>(std::floor(double(t) * size));
    return static_cast<size_t>(((i % size) + size) % size);
  };
  const size_t x = wrap(uv.x, texture.width), y = wrap(uv.y, texture.height);
  return float(texture.rgba[(y * size_t(texture.width) + x) * 4 + 3]) / 255.0f;
}

const char* to_string(AnalyticShape::Kind kind) {
  switch (kind) {
    case AnalyticShape::Kind::None:
      return "none";
    case AnalyticShape::Kind::Sphere:
      return "sphere";
  }
  return "unknown";
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

size_t Scene::analytic_caster_count() const {
  size_t n = 0;
  for (const auto& m : meshes)
    if (m.casts_shadow && m.analytic.has()) ++n;
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

}  // namespace sb::core

namespace sb::core {

void fit_clip_planes(Camera& camera, const Bounds& bounds) {
  if (bounds.empty()) return;
  float farthest = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? bounds.hi.x : bounds.lo.x, (i & 2) ? bounds.hi.y : bounds.lo.y,
                           (i & 4) ? bounds.hi.z : bounds.lo.z);
    farthest = std::max(farthest, glm::distance(camera.eye, corner));
  }
  const float nearest = glm::distance(camera.eye, glm::clamp(camera.eye, bounds.lo, bounds.hi));
  camera.far_plane = 1.05f * farthest;
  camera.near_plane = std::max(0.5f * nearest, 1e-4f * camera.far_plane);
}

}  // namespace sb::core
