#include "core/scene_setup_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sb::core {
namespace {

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool in_range(const glm::vec3& v) {
  return finite(v) && std::fabs(v.x) <= kLargestCoordinate &&
         std::fabs(v.y) <= kLargestCoordinate && std::fabs(v.z) <= kLargestCoordinate;
}

std::string str(const glm::vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%g, %g, %g)", double(v.x), double(v.y), double(v.z));
  return buf;
}

}  // namespace

std::string camera_problem(const Camera& c) {
  if (!in_range(c.eye)) return "camera: eye " + str(c.eye) + " is not finite or too far out";
  if (!in_range(c.target))
    return "camera: target " + str(c.target) + " is not finite or too far out";
  if (!finite(c.up)) return "camera: up " + str(c.up) + " is not finite";
  const glm::vec3 view = c.target - c.eye;
  const float scale = std::max({1.0f, glm::length(c.eye), glm::length(c.target)});
  if (!(glm::length(view) > 1e-6f * scale))
    return "camera: eye " + str(c.eye) + " equals target " + str(c.target);
  const float up = glm::length(c.up);
  if (!(up > 0.0f)) return "camera: up is the zero vector";
  if (!(glm::length(glm::cross(glm::normalize(view), c.up / up)) > 1e-4f))
    return "camera: up " + str(c.up) + " is parallel to the view direction " + str(view);
  if (!(c.fov_y_degrees >= 1e-3f && c.fov_y_degrees < 180.0f))
    return "camera: fov_y " + std::to_string(c.fov_y_degrees) + " degrees is outside [0.001, 180)";
  if (!(c.near_plane > 0.0f && std::isfinite(c.far_plane) && c.far_plane > c.near_plane))
    return "camera: expected 0 < near < far, found near " + std::to_string(c.near_plane) +
           ", far " + std::to_string(c.far_plane);
  return "";
}

std::string scene_setup_problem(const Scene& scene) {
  // Geometry first: a generator or importer derives the camera and the light
  // from it, so their problems usually start here.
  size_t proper = 0;
  for (const Mesh& m : scene.meshes) {
    for (const glm::vec3& p : m.positions)
      if (!in_range(p))
        return "mesh '" + m.name + "': a vertex at " + str(p) + " is not finite or too far out";
    for (size_t t = 0; t + 2 < m.indices.size() && proper == 0; t += 3) {
      const glm::vec3 a = m.positions.at(m.indices[t]), b = m.positions.at(m.indices[t + 1]),
                      c = m.positions.at(m.indices[t + 2]);
      if (glm::length(glm::cross(b - a, c - a)) > 0.0f) ++proper;
    }
  }
  if (proper == 0) return "the scene has no triangle of non-zero area";
  const AreaLight& l = scene.light;
  if (!in_range(l.center) || !finite(l.half_u) || !finite(l.half_v) || !finite(l.target))
    return "light: centre " + str(l.center) + " or its size is not finite or too far out";
  return camera_problem(scene.camera);
}

}  // namespace sb::core
