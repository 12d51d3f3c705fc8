// Ray-traced reference throughput on the default sphere grid (81 UV spheres of
// 760 triangles over a ground plane), 800×600 G-buffer made by primary ray
// casting (not timed). Arg = samples per pixel; Mrays/s counts shadow rays.
//
// BM_AdaptiveAtUniformNoise is the adaptive reference (reference.adaptive,
// 4-, 16- and 64-sample pilots, up to 1024) with its target set to the largest standard
// error of the uniform 1024-spp reference (computed once, untimed): the same
// worst-pixel noise. Its `vs_uniform_1024` counter is its time over
// BM_Reference/spp:1024's in the same process (run them together:
//   build/bench/bench_reference --benchmark_filter='1024|Adaptive').
#include <benchmark/benchmark.h>

#include <algorithm>
#include <utility>

#include "reference/reference.h"
#include "reference_workload.h"

namespace {

const sb::bench::SceneWorkload& workload() {
  static const sb::bench::SceneWorkload w = sb::bench::default_sphere_grid();
  return w;
}

double max_std_error(const sb::reference::Result& r) {
  float most = 0;
  for (float v : r.std_error.data) most = std::max(most, v);
  return double(most);
}

// Seconds per uniform 1024-spp reference, from BM_Reference when it ran.
double uniform_1024_seconds = 0;

void BM_Reference(benchmark::State& state) {
  const sb::bench::SceneWorkload& w = workload();
  const sb::reference::Settings settings{int(state.range(0)), 1};
  double traced = 0;
  sb::reference::Result last;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    sb::reference::Result r =
        sb::reference::compute(w.scene, w.gbuffer.positions, w.gbuffer.normals, settings);
    benchmark::DoNotOptimize(r.visibility.data.data());
    traced += r.seconds;
    last = std::move(r);
  }
  const double rays = double(w.covered) * settings.spp;
  state.counters["Mrays/s"] =
      benchmark::Counter(rays * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["trace_s"] = traced / double(state.iterations());
  state.counters["max_std_error"] = max_std_error(last);
  state.counters["penumbra_rms_std_error"] = last.penumbra_rms_std_error;
  if (settings.spp == 1024) uniform_1024_seconds = traced / double(state.iterations());
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

void BM_AdaptiveAtUniformNoise(benchmark::State& state) {
  const sb::bench::SceneWorkload& w = workload();
  static const double target = max_std_error(
      sb::reference::compute(w.scene, w.gbuffer.positions, w.gbuffer.normals, {1024, 1}));
  sb::reference::Settings settings{1024, 1};
  settings.adaptive = true;
  settings.pilot_spp = int(state.range(0));
  settings.target_std_error = target;
  double traced = 0, worst = 0, mean_spp = 0, rms = 0;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    const sb::reference::Result r =
        sb::reference::compute(w.scene, w.gbuffer.positions, w.gbuffer.normals, settings);
    benchmark::DoNotOptimize(r.visibility.data.data());
    traced += r.seconds;
    worst = max_std_error(r);
    mean_spp = r.mean_spp;
    rms = r.penumbra_rms_std_error;
  }
  const double seconds = traced / double(state.iterations());
  state.counters["trace_s"] = seconds;
  state.counters["target_std_error"] = target;
  state.counters["max_std_error"] = worst;
  state.counters["penumbra_rms_std_error"] = rms;
  state.counters["mean_spp"] = mean_spp;
  if (uniform_1024_seconds > 0) state.counters["vs_uniform_1024"] = seconds / uniform_1024_seconds;
}

BENCHMARK(BM_AdaptiveAtUniformNoise)
    ->ArgName("pilot")
    ->Arg(4)
    ->Arg(16)
    ->Arg(64)
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
