#include "scenes/receiver_inference.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace sb {

using core::Mesh;
using core::Scene;

std::optional<glm::dvec4> mesh_plane(const Mesh& m, double eps) {
  glm::dvec3 n(0.0);
  double best = 0.0;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const glm::dvec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                     c = m.positions[m.indices[3 * t + 2]];
    const glm::dvec3 cr = glm::cross(b - a, c - a);
    const double len = glm::length(cr);
    if (len > best) {
      best = len;
      n = cr / len;
    }
  }
  if (best == 0.0) return std::nullopt;
  const double d = -glm::dot(n, glm::dvec3(m.positions[m.indices[0]]));
  for (uint32_t i : m.indices)
    if (std::fabs(glm::dot(n, glm::dvec3(m.positions[i])) + d) > eps) return std::nullopt;
  return glm::dvec4(n, d);
}

namespace {

// Each vertex some triangle uses, once per mesh.
std::vector<glm::vec3> referenced_vertices(const Scene& scene) {
  std::vector<glm::vec3> points;
  std::vector<char> seen;
  for (const Mesh& m : scene.meshes) {
    seen.assign(m.positions.size(), 0);
    for (uint32_t v : m.indices) {
      if (seen[v] != 0) continue;
      seen[v] = 1;
      points.push_back(m.positions[v]);
    }
  }
  return points;
}

}  // namespace

bool can_shadow_nothing(const Scene& scene, size_t mesh) { return ShadowNothingTest(scene)(mesh); }

ShadowNothingTest::ShadowNothingTest(const Scene& scene)
    : scene_(scene), bounds_(scene.bounds()), vertices_(referenced_vertices(scene)) {}

bool ShadowNothingTest::operator()(size_t mesh) const {
  const Mesh& m = scene_.meshes.at(mesh);
  if (bounds_.empty() || m.triangle_count() == 0) return false;
  // Flatness within a millionth of the scene's size. Geometry sunk into the
  // plane by up to a thousandth (a tree's roots, a model resting a little
  // into its floor) is hidden by it from a camera on the light's side.
  const double eps = 1e-6 * std::max(double(bounds_.radius()), 1e-6);
  const double sunk = 1e-3 * std::max(double(bounds_.radius()), 1e-6);
  const auto plane = mesh_plane(m, eps);
  if (!plane) return false;
  glm::dvec3 n(*plane);
  double d = plane->w;
  if (scene_.light.is_sun()) {
    // The sun wholly on one side of the plane, at infinity: only the
    // directions count.
    const int side = core::sun_side(scene_.light, n);
    if (side == 0) return false;
    if (side < 0) {
      n = -n;
      d = -d;
    }
  } else {
    const glm::dvec3 corners[4] = {scene_.light.point(0, 0), scene_.light.point(1, 0),
                                   scene_.light.point(0, 1), scene_.light.point(1, 1)};
    if (glm::dot(n, corners[0]) + d < 0.0) {  // orient towards the light
      n = -n;
      d = -d;
    }
    for (const auto& c : corners)
      if (!(glm::dot(n, c) + d > eps)) return false;
  }
  if (!(glm::dot(n, glm::dvec3(scene_.camera.eye)) + d > eps)) return false;
  // Every other mesh on the light's side or sunk by less than `sunk`. The
  // mesh's own vertices, within eps of its plane, pass that test too, so
  // the tree holds them as well.
  return !vertices_.any_below(n, d, sunk);
}

std::vector<std::string> infer_receivers(Scene& scene) {
  // Decided on the scene as loaded, then applied: each decision is exact on
  // its own, since a receiver still stands where it stood.
  std::vector<size_t> receivers;
  const ShadowNothingTest shadows_nothing(scene);
  for (size_t i = 0; i < scene.meshes.size(); ++i)
    if (scene.meshes[i].casts_shadow && shadows_nothing(i)) receivers.push_back(i);
  std::vector<std::string> names;
  for (size_t i : receivers) {
    scene.meshes[i].casts_shadow = false;
    names.push_back(scene.meshes[i].name);
  }
  return names;
}

}  // namespace sb
