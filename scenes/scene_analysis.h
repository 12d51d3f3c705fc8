#pragma once
// What a scene has, computed only as far as the plan's techniques ask:
// closedness of the casters when some technique needs closed casters, edge
// adjacency when some technique that will actually run needs it.
#include <string>
#include <vector>

#include "core/registry.h"
#include "scenes/topology.h"

namespace sb {

// A planar mesh with every caster on the light's side of its plane.
struct PlanarReceiver {
  std::string mesh;
  glm::vec4 plane{0.0f};  // (n, d): n·x + d = 0, n towards the casters
};

struct SceneCapabilities {
  bool closedness_checked = false;
  bool adjacency_built = false;
  bool receiver_checked = false;
  bool has_planar_receiver = false;
  PlanarReceiver receiver;
  std::vector<MeshTopology> topology;            // per mesh, when closedness_checked
  std::vector<std::vector<uint32_t>> adjacency;  // per mesh (casters only), when adjacency_built
  std::vector<std::string> log;                  // one line per thing built
};

// Checks closedness if any of `techniques` needs closed casters or adjacency,
// and looks for a planar receiver if any needs one.
SceneCapabilities check_closedness(const Scene& scene,
                                   const std::vector<const TechniqueInfo*>& techniques);
// The first planar mesh that has every caster vertex on its light side.
bool find_planar_receiver(const Scene& scene, PlanarReceiver& out);
// "" when the technique can run on the scene, else why not, e.g.
// "shadow_volume needs closed casters: mesh 'leaves' has 1834 boundary edges".
std::string unmet_needs(const Scene& scene, const SceneCapabilities& caps, const TechniqueInfo& t);
// Builds adjacency if any of `running` needs it.
void build_adjacency_if_needed(const Scene& scene, const std::vector<const TechniqueInfo*>& running,
                               SceneCapabilities& caps);

// Process-wide counters of derived data built (for tests and logs).
struct DerivedDataCounters {
  size_t closedness_checks = 0;  // meshes analysed
  size_t adjacency_builds = 0;   // meshes given adjacency
  size_t receiver_searches = 0;  // scenes searched for a planar receiver
};
DerivedDataCounters& derived_data_counters();

}  // namespace sb
