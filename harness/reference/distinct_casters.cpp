#include "reference/distinct_casters.h"

#include <cstring>
#include <unordered_map>
#include <vector>

#include "core/hash.h"

namespace sb::reference::detail {

using core::Mesh;
using core::Scene;

namespace {

template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Everything of a caster the reference reads: its triangles, its mask (a
// mask's uvs and texture) and its shape, and whether it may be closed
// (double-sided casters never are).
bool same_occluder(const Mesh& a, const Mesh& b) {
  if (!same_bytes(a.positions, b.positions) || !same_bytes(a.indices, b.indices)) return false;
  if (a.alpha_tested() != b.alpha_tested() || a.double_sided != b.double_sided) return false;
  if (a.alpha_tested() && (a.base_color_texture != b.base_color_texture ||
                           a.alpha_cutoff != b.alpha_cutoff || !same_bytes(a.uvs, b.uvs)))
    return false;
  const core::AnalyticShape &x = a.analytic, &y = b.analytic;
  return x.kind == y.kind && (!x.has() || (x.center == y.center && x.radius == y.radius));
}

uint64_t triangles_hash(const Mesh& m) {
  core::Hasher h;
  h.add(m.positions.data(), m.positions.size() * sizeof(glm::vec3));
  h.add(m.indices.data(), m.indices.size() * sizeof(uint32_t));
  return h.value();
}

}  // namespace

std::optional<Scene> without_repeated_casters(const Scene& scene) {
  // Casters by the hash of their triangles; a repeat must then match one of
  // those with the same hash in every byte.
  std::unordered_multimap<uint64_t, size_t> seen;
  std::vector<bool> repeated(scene.meshes.size(), false);
  bool any = false;
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const Mesh& m = scene.meshes[i];
    if (!m.casts_shadow || m.indices.empty()) continue;
    const uint64_t h = triangles_hash(m);
    const auto [lo, hi] = seen.equal_range(h);
    for (auto it = lo; it != hi && !repeated[i]; ++it)
      repeated[i] = same_occluder(scene.meshes[it->second], m);
    if (repeated[i])
      any = true;
    else
      seen.emplace(h, i);
  }
  if (!any) return std::nullopt;
  Scene out;
  out.name = scene.name;
  out.textures = scene.textures;
  out.light = scene.light;
  out.camera = scene.camera;
  out.ambient = scene.ambient;
  out.inputs = scene.inputs;
  for (size_t i = 0; i < scene.meshes.size(); ++i)
    if (!repeated[i]) out.meshes.push_back(scene.meshes[i]);
  return out;
}

}  // namespace sb::reference::detail
