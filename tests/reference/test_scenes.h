#pragma once
// Small scenes and hand-made G-buffers for the reference tests.
#include <cmath>
#include <numbers>
#include <utility>

#include "core/image.h"
#include "core/scene.h"

namespace sbtest {

inline sb::core::Mesh quad(const std::string& name, glm::vec3 a, glm::vec3 b, glm::vec3 c,
                           glm::vec3 d, bool casts) {
  sb::core::Mesh m;
  m.name = name;
  m.positions = {a, b, c, d};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.casts_shadow = casts;
  return m;
}

inline sb::core::Mesh sphere(glm::vec3 center, float radius, int slices, int stacks) {
  sb::core::Mesh m;
  m.name = "sphere";
  for (int i = 0; i <= stacks; ++i)
    for (int j = 0; j <= slices; ++j) {
      const float th = std::numbers::pi_v<float> * float(i) / float(stacks);
      const float ph = 2.0f * std::numbers::pi_v<float> * float(j) / float(slices);
      m.positions.push_back(center + radius * glm::vec3(std::sin(th) * std::cos(ph), std::cos(th),
                                                        -std::sin(th) * std::sin(ph)));
    }
  const auto at = [&](int i, int j) { return uint32_t(i * (slices + 1) + j); };
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j)
      m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j),
                                         at(i + 1, j + 1), at(i, j + 1)});
  return m;
}

// A 2×2 square light at height 10 over the origin.
inline sb::core::AreaLight square_light() {
  sb::core::AreaLight l;
  l.center = {0, 10, 0};
  l.half_u = {1, 0, 0};
  l.half_v = {0, 0, 1};
  return l;
}

// `caster` over a ground plane (the receiver, not a caster), lit from above
// by a 2.4 × 2.4 light, camera above.
inline sb::core::Scene over_plane(sb::core::Mesh caster) {
  sb::core::Scene s;
  s.meshes.push_back(quad("ground", {-6, 0, -6}, {-6, 0, 6}, {6, 0, 6}, {6, 0, -6}, false));
  s.meshes.push_back(std::move(caster));
  s.light.center = {0.6f, 6.0f, 0.3f};
  s.light.half_u = {1.2f, 0, 0};
  s.light.half_v = {0, 0, 1.2f};
  s.camera.eye = {0, 9, 5};
  s.camera.target = {0, 0, 0};
  s.camera.fov_y_degrees = 40.0f;
  return s;
}

// A speck over ground point p: a horizontal quad, half sizes hx (along x)
// and hz, 0.05 along the way from p to the light's centre, where the
// pyramid (or triangle) from p to a light of the over_plane() size is about
// 0.02 across.
inline sb::core::Mesh speck_over(const sb::core::Scene& scene, glm::vec3 p, float hx, float hz) {
  const glm::vec3 c = p + 0.05f / glm::length(scene.light.center - p) * (scene.light.center - p);
  return quad("speck", c + glm::vec3(-hx, 0, -hz), c + glm::vec3(hx, 0, -hz),
              c + glm::vec3(hx, 0, hz), c + glm::vec3(-hx, 0, hz), true);
}

// The surface point of a G-buffer pixel (RGBA32F positions).
inline glm::vec3 position_at(const sb::core::ImageF& positions, size_t pix) {
  return {positions.data[pix * 4], positions.data[pix * 4 + 1], positions.data[pix * 4 + 2]};
}

// A sphere floating over the ground plane.
inline sb::core::Scene sphere_over_plane() {
  return over_plane(sphere({0, 1.6f, 0}, 1.0f, 24, 16));
}

}  // namespace sbtest
