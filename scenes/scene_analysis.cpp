#include "scenes/scene_analysis.h"

#include <algorithm>
#include <cmath>

#include "scenes/receiver_inference.h"

namespace sb {

DerivedDataCounters& derived_data_counters() {
  static DerivedDataCounters counters;
  return counters;
}

bool find_planar_receiver(const Scene& scene, PlanarReceiver& out) {
  const Bounds all = scene.bounds();
  const float eps = 1e-5f * std::max(all.radius(), 1e-6f);
  for (const auto& m : scene.meshes) {
    if (m.triangle_count() == 0) continue;
    const auto plane = mesh_plane(m, double(eps));
    if (!plane) continue;
    glm::vec3 n(*plane);
    auto d = float(plane->w);
    if (glm::dot(n, scene.light.center) + d < 0.0f) {  // orient towards the light
      n = -n;
      d = -d;
    }
    bool below_all = true;
    for (const auto& c : scene.meshes) {
      if (!c.casts_shadow || &c == &m) continue;
      for (const auto& p : c.positions) below_all = below_all && glm::dot(n, p) + d > -eps;
    }
    if (!below_all) continue;
    out.mesh = m.name;
    out.plane = glm::vec4(n, d);
    return true;
  }
  return false;
}

SceneCapabilities check_closedness(const Scene& scene,
                                   const std::vector<const TechniqueInfo*>& techniques) {
  SceneCapabilities caps;
  bool wants_receiver = false;
  for (const auto* t : techniques) wants_receiver = wants_receiver || t->needs.planar_receiver;
  if (wants_receiver) {
    caps.receiver_checked = true;
    ++derived_data_counters().receiver_searches;
    caps.has_planar_receiver = find_planar_receiver(scene, caps.receiver);
    caps.log.push_back(caps.has_planar_receiver
                           ? "planar receiver: mesh '" + caps.receiver.mesh + "'"
                           : std::string("no planar receiver"));
  }
  bool needed = false;
  for (const auto* t : techniques)
    needed =
        needed || t->needs.closed_casters || t->needs.edge_adjacency || t->needs.caster_closedness;
  if (!needed) return caps;
  caps.closedness_checked = true;
  size_t open = 0;
  for (const auto& m : scene.meshes) {
    caps.topology.push_back(m.casts_shadow ? analyse_topology(m) : MeshTopology{});
    if (m.casts_shadow) ++derived_data_counters().closedness_checks;
    if (!caps.topology.back().closed()) ++open;
  }
  caps.log.push_back("checked closedness of the casters (" + std::to_string(open) + " open)");
  return caps;
}

std::string unmet_needs(const Scene& scene, const SceneCapabilities& caps, const TechniqueInfo& t) {
  if (t.needs.planar_receiver && !caps.has_planar_receiver)
    return t.name + " needs a planar receiver under every caster; the scene has none";
  if (t.needs.closed_casters) {
    if (!caps.closedness_checked)
      return t.name + " needs closed casters, but closedness was not checked";
    for (size_t i = 0; i < scene.meshes.size(); ++i) {
      const auto& m = scene.meshes[i];
      const auto& topo = caps.topology[i];
      if (!m.casts_shadow || topo.closed()) continue;
      std::string what;
      if (topo.boundary_edges) what = std::to_string(topo.boundary_edges) + " boundary edges";
      if (topo.nonmanifold_edges)
        what += (what.empty() ? "" : ", ") + std::to_string(topo.nonmanifold_edges) +
                " non-manifold edges";
      if (topo.inconsistent_edges)
        what += (what.empty() ? "" : ", ") + std::to_string(topo.inconsistent_edges) +
                " inconsistently wound edges";
      return t.name + " needs closed casters: mesh '" + m.name + "' has " + what;
    }
  }
  if (t.needs.opaque_casters)
    for (const auto& m : scene.meshes)
      if (m.casts_shadow && m.alpha_tested())
        return t.name + " cannot honour alpha masks: mesh '" + m.name + "' is alpha-tested";
  return "";
}

void build_adjacency_if_needed(const Scene& scene, const std::vector<const TechniqueInfo*>& running,
                               SceneCapabilities& caps) {
  bool needed = false;
  for (const auto* t : running) needed = needed || t->needs.edge_adjacency;
  if (!needed || caps.adjacency_built) return;
  caps.adjacency.assign(scene.meshes.size(), {});
  size_t triangles = 0;
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    if (!scene.meshes[i].casts_shadow) continue;
    caps.adjacency[i] = build_adjacency_indices(scene.meshes[i]);
    triangles += scene.meshes[i].triangle_count();
    ++derived_data_counters().adjacency_builds;
  }
  caps.adjacency_built = true;
  caps.log.push_back("built edge adjacency for " + std::to_string(triangles) + " caster triangles");
}

}  // namespace sb
