#include "scenes/scene_analysis.h"

namespace sb {

DerivedDataCounters& derived_data_counters() {
  static DerivedDataCounters counters;
  return counters;
}

SceneCapabilities check_closedness(const Scene& scene,
                                   const std::vector<const TechniqueInfo*>& techniques) {
  SceneCapabilities caps;
  bool needed = false;
  for (const auto* t : techniques)
    needed = needed || t->needs.closed_casters || t->needs.edge_adjacency;
  if (!needed) return caps;
  caps.closedness_checked = true;
  size_t open = 0;
  for (const auto& m : scene.meshes) {
    caps.topology.push_back(m.casts_shadow ? analyse_topology(m) : MeshTopology{});
    if (m.casts_shadow) ++derived_data_counters().closedness_checks;
    if (!caps.topology.back().closed()) ++open;
  }
  caps.log.push_back("checked closedness of " + std::to_string(scene.meshes.size()) + " meshes (" +
                     std::to_string(open) + " open)");
  return caps;
}

std::string unmet_needs(const Scene& scene, const SceneCapabilities& caps, const TechniqueInfo& t) {
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
