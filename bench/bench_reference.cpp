// Ray-traced reference throughput on the default sphere grid (81 UV spheres of
// 760 triangles over a ground plane), 800×600 G-buffer made by primary ray
// casting (not timed). Arg = samples per pixel; Mrays/s counts shadow rays.
//
// BM_RobustOverFast is the cost of Embree's robust mode (embree_scene.h):
//   build/bench/bench_reference --benchmark_filter=Robust --benchmark_repetitions=5
//
// cpu_s is the process's CPU time (user + system, all threads) per
// reference: on a machine shared with other work it moves less than the
// wall time (trace_s), which counts the time other processes ran.
//
// BM_AdaptiveAtUniformNoise is the adaptive reference (reference.adaptive,
// 4-, 16- and 64-sample pilots, up to 1024) with its target set to the largest standard
// error of the uniform 1024-spp reference (computed once, untimed): the same
// worst-pixel noise. Its `vs_uniform_1024` counter is its time over
// BM_Reference/spp:1024's in the same process (run them together:
//   build/bench/bench_reference --benchmark_filter='1024|Adaptive').
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "reference/embree_isa.h"
#include "reference/embree_scene.h"
#include "reference/pixel_rays.h"
#include "reference/reference.h"
#include "reference/stratify.h"
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

// The process's user + system time, all threads: on a shared machine it
// counts only the time this process ran, unlike wall time.
double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return seconds(u.ru_utime) + seconds(u.ru_stime);
}

// Seconds per uniform 1024-spp reference, from BM_Reference when it ran.
double uniform_1024_seconds = 0;

void BM_Reference(benchmark::State& state) {
  const sb::bench::SceneWorkload& w = workload();
  const sb::reference::Settings settings{int(state.range(0)), 1};
  double traced = 0, cpu = 0;
  sb::reference::Result last;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    const double cpu0 = process_cpu_seconds();
    sb::reference::Result r =
        sb::reference::compute(w.scene, w.gbuffer.positions, w.gbuffer.normals, settings);
    cpu += process_cpu_seconds() - cpu0;
    benchmark::DoNotOptimize(r.visibility.data.data());
    traced += r.seconds;
    last = std::move(r);
  }
  const double rays = double(w.covered) * settings.spp;
  state.counters["Mrays/s"] =
      benchmark::Counter(rays * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["trace_s"] = traced / double(state.iterations());
  state.counters["cpu_s"] = cpu / double(state.iterations());
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
  double traced = 0, cpu = 0, worst = 0, mean_spp = 0, rms = 0;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    const double cpu0 = process_cpu_seconds();
    const sb::reference::Result r =
        sb::reference::compute(w.scene, w.gbuffer.positions, w.gbuffer.normals, settings);
    cpu += process_cpu_seconds() - cpu0;
    benchmark::DoNotOptimize(r.visibility.data.data());
    traced += r.seconds;
    worst = max_std_error(r);
    mean_spp = r.mean_spp;
    rms = r.penumbra_rms_std_error;
  }
  const double seconds = traced / double(state.iterations());
  state.counters["trace_s"] = seconds;
  state.counters["cpu_s"] = cpu / double(state.iterations());
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

// The uniform reference's work (BVH build and every covered pixel's spp
// rays, on all threads) under Embree's robust traversal, which the reference
// uses, and under its default fast one, from the same rays.
// robust_over_fast: total robust time over total fast time, the two taking
// turns (the order swaps every iteration, so a slower stretch of a shared
// machine hits both); robust_over_fast_cpu the same in the process's CPU
// time, which other processes on the machine disturb less. pixels_differing, rays_differing and
// mean_dV compare the two images (robust − fast, over covered pixels).
struct TracedImage {
  std::vector<uint32_t> reached;  // rays that reached the light, per pixel
  double seconds = 0;             // wall time
  double cpu_seconds = 0;         // user + system time of all threads
};

TracedImage trace_with(const sb::bench::SceneWorkload& w, sb::reference::detail::Device& device,
                       sb::reference::detail::Traversal traversal, int spp) {
  namespace d = sb::reference::detail;
  const auto t0 = std::chrono::steady_clock::now();
  const double cpu0 = process_cpu_seconds();
  const d::FlatScene casters(
      device, w.scene, [](const sb::core::Mesh& m) { return m.casts_shadow; }, true, traversal);
  const d::Layout layout = d::make_layout(spp);
  const d::RaySetup setup(w.scene, casters, layout, w.gbuffer.positions, w.gbuffer.normals, 1);
  const sb::core::ImageF& positions = w.gbuffer.positions;
  TracedImage out;
  out.reached.assign(positions.pixel_count(), 0);
  std::vector<uint32_t> all(static_cast<size_t>(spp));
  for (size_t i = 0; i < all.size(); ++i) all[i] = uint32_t(i);
  tbb::parallel_for(tbb::blocked_range2d<int>(0, positions.height, 8, 0, positions.width, 8),
                    [&](const tbb::blocked_range2d<int>& tile) {
                      const d::FtzDazScope ftz;
                      d::PixelRays rays(setup);
                      std::vector<uint8_t> reached(all.size());
                      for (int y = tile.rows().begin(); y < tile.rows().end(); ++y)
                        for (int x = tile.cols().begin(); x < tile.cols().end(); ++x) {
                          const size_t pix = size_t(y) * size_t(positions.width) + size_t(x);
                          if (!d::covered(positions, pix)) continue;
                          rays.start(pix);
                          rays.trace(all.data(), all.size(), reached.data());
                          uint32_t count = 0;
                          for (const uint8_t r : reached) count += r;
                          out.reached[pix] = count;
                        }
                    });
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.cpu_seconds = process_cpu_seconds() - cpu0;
  return out;
}

void BM_RobustOverFast(benchmark::State& state) {
  namespace d = sb::reference::detail;
  const sb::bench::SceneWorkload& w = workload();
  const int spp = int(state.range(0));
  const std::string isa = sb::reference::resolve_isa(sb::reference::default_embree_config());
  d::Device device(isa);
  state.SetLabel("isa=" + isa);
  double robust = 0, fast = 0, robust_cpu = 0, fast_cpu = 0;
  TracedImage last_robust, last_fast;
  bool robust_first = true;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    if (robust_first) {
      last_robust = trace_with(w, device, d::Traversal::Robust, spp);
      last_fast = trace_with(w, device, d::Traversal::Fast, spp);
    } else {
      last_fast = trace_with(w, device, d::Traversal::Fast, spp);
      last_robust = trace_with(w, device, d::Traversal::Robust, spp);
    }
    robust_first = !robust_first;
    robust += last_robust.seconds;
    fast += last_fast.seconds;
    robust_cpu += last_robust.cpu_seconds;
    fast_cpu += last_fast.cpu_seconds;
  }
  double pixels = 0, rays = 0, sum_dv = 0;
  for (size_t i = 0; i < last_robust.reached.size(); ++i) {
    const double dv = double(last_robust.reached[i]) - double(last_fast.reached[i]);
    pixels += dv != 0.0;
    rays += std::fabs(dv);
    sum_dv += dv / spp;
  }
  const double iterations = double(state.iterations());
  state.counters["robust_s"] = robust / iterations;
  state.counters["fast_s"] = fast / iterations;
  state.counters["robust_over_fast"] = robust / fast;
  state.counters["robust_over_fast_cpu"] = robust_cpu / fast_cpu;
  state.counters["pixels_differing"] = pixels;
  state.counters["rays_differing"] = rays;
  state.counters["mean_dV"] = sum_dv / double(w.covered);
  state.counters["covered_px"] = double(w.covered);
}

BENCHMARK(BM_RobustOverFast)
    ->ArgName("spp")
    ->Arg(64)
    ->Arg(256)
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
