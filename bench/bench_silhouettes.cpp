// shadow_volume's CPU work per frame, per silhouette mode and tessellation:
// extract_silhouette (loops and lit region) and append_volume (the
// triangles uploaded), for one UV sphere under the sphere grid's light. The
// smooth/discrete ratio at equal triangle count is the number to compare with
// Mattausch et al. 2012, Table 1 (docs/shadow_volumes.md).
#include <benchmark/benchmark.h>

#include "scenes/sphere_grid.h"
#include "scenes/topology.h"
#include "shadow_volume/silhouette.h"
#include "shadow_volume/volume_mesh.h"

namespace {

using sb::techniques::shadow_volume::SilhouetteMode;

void silhouette_and_volume(benchmark::State& state, SilhouetteMode mode) {
  // 2·slices·(stacks − 1) triangles, slices = 2·stacks.
  const int stacks = int(state.range(0));
  const sb::core::Mesh sphere = sb::make_uv_sphere("s", {0, 1.2f, 0}, 0.5f, 2 * stacks, stacks);
  const sb::techniques::shadow_volume::SilhouetteMesh shape =
      sb::techniques::shadow_volume::make_silhouette_mesh(sphere, sb::mesh_edges(sphere));
  sb::techniques::shadow_volume::SilhouetteSettings settings;
  settings.mode = mode;
  const glm::vec3 light(3.5f, 10.0f, 2.5f);
  sb::techniques::shadow_volume::Silhouette silhouette;
  sb::techniques::shadow_volume::VolumeVertices volume;
  for (auto _ : state) {
    sb::techniques::shadow_volume::extract_silhouette(shape, light, settings, silhouette);
    volume.clear();
    sb::techniques::shadow_volume::append_volume(silhouette, light, true, volume);
    benchmark::DoNotOptimize(volume.vertices.data());
  }
  state.counters["triangles"] = double(sphere.triangle_count());
  state.counters["volume_vertices"] = double(volume.vertices.size());
}

void BM_Discrete(benchmark::State& s) { silhouette_and_volume(s, SilhouetteMode::Discrete); }
void BM_Accurate(benchmark::State& s) { silhouette_and_volume(s, SilhouetteMode::Accurate); }
void BM_Smooth(benchmark::State& s) { silhouette_and_volume(s, SilhouetteMode::Smooth); }

// 80 to 6,240 triangles per sphere, around what configs/mattausch12.json sweeps.
BENCHMARK(BM_Discrete)->Arg(5)->Arg(9)->Arg(17)->Arg(28)->Arg(40);
BENCHMARK(BM_Accurate)->Arg(5)->Arg(9)->Arg(17)->Arg(28)->Arg(40);
BENCHMARK(BM_Smooth)->Arg(5)->Arg(9)->Arg(17)->Arg(28)->Arg(40);

}  // namespace

BENCHMARK_MAIN();
