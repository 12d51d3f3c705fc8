#pragma once
// The needs the harness provides (plugin/needs.h, namespace need): what each
// computes from a scene, and when. The planner resolves a technique's needs
// against these and any a plugin registered (plan/need_resolution.h).
#include <string>
#include <vector>

#include "plugin/need_data.h"
#include "plugin/needs.h"
#include "scenes/topology.h"

namespace sb {

// need::kCasterClosedness's data: per scene mesh (receivers: default).
using CasterTopology = std::vector<MeshTopology>;
// The first planar mesh that has every caster vertex on its light side.
bool find_planar_receiver(const core::Scene& scene, plugin::PlanarReceiver& out);

const std::vector<plugin::NeedProvider>& builtin_need_providers();

// The packed std430 records of need::kSilhouetteEdges (plugin/silhouette_edges.h):
// 16 floats per edge, and per mesh its first edge and count.
struct SilhouetteEdgeRecords {
  std::vector<float> floats;
  std::vector<std::pair<int, int>> mesh_ranges;  // (first edge, count) per mesh
};
SilhouetteEdgeRecords pack_silhouette_edges(const core::Scene& scene);

// Process-wide counters of derived data built (for tests and logs).
struct DerivedDataCounters {
  size_t closedness_checks = 0;   // meshes analysed
  size_t adjacency_builds = 0;    // meshes given adjacency
  size_t receiver_searches = 0;   // scenes searched for a planar receiver
  size_t silhouette_uploads = 0;  // scenes whose edges went to the GPU
};
DerivedDataCounters& derived_data_counters();

}  // namespace sb
