// Ray-traced reference throughput on the default sphere grid (81 UV spheres of
// 760 triangles over a ground plane), 800×600 G-buffer made by primary ray
// casting (not timed). Arg = samples per pixel; Mrays/s counts shadow rays.
#include <benchmark/benchmark.h>

#include "reference/reference.h"
#include "reference_workload.h"

namespace {

const sb::bench::SceneWorkload& workload() {
  static const sb::bench::SceneWorkload w = sb::bench::default_sphere_grid();
  return w;
}

void BM_Reference(benchmark::State& state) {
  const sb::bench::SceneWorkload& w = workload();
  const sb::reference::Settings settings{int(state.range(0)), 1};
  double traced = 0;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    const sb::reference::Result r =
        sb::reference::compute(w.scene, w.gbuffer.positions, w.gbuffer.normals, settings);
    benchmark::DoNotOptimize(r.visibility.data.data());
    traced += r.seconds;
  }
  const double rays = double(w.covered) * settings.spp;
  state.counters["Mrays/s"] =
      benchmark::Counter(rays * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["trace_s"] = traced / double(state.iterations());
  state.counters["covered_px"] = double(w.covered);
  state.counters["caster_tris"] = double(w.scene.caster_triangle_count());
}

BENCHMARK(BM_Reference)
    ->ArgName("spp")
    ->Arg(64)
    ->Arg(256)
    ->Arg(1024)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The cache key hashes both 800×600 buffers (13 MB) on every get().
void BM_CacheKey(benchmark::State& state) {
  const sb::bench::SceneWorkload& w = workload();
  for (auto _ : state)  // NOLINT(clang-analyzer-deadcode.DeadStores)
    benchmark::DoNotOptimize(
        sb::reference::cache_key(w.scene, w.gbuffer.positions, w.gbuffer.normals, {256, 1}));
}

BENCHMARK(BM_CacheKey)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
