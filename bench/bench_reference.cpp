// Ray-traced reference throughput on the default sphere grid (81 UV spheres of
// 760 triangles over a ground plane), 800×600 G-buffer made by primary ray
// casting (not timed). Arg = samples per pixel; Mrays/s counts shadow rays.
#include <benchmark/benchmark.h>

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "core/params.h"
#include "core/scene_types.h"
#include "reference/reference.h"

namespace {

struct Workload {
  sb::Scene scene;
  sb::reference::GBuffer gbuffer;
  size_t covered = 0;
};

const Workload& workload() {
  static const Workload w = [] {
    const sb::SceneType* type = sb::find_scene_type("sphere_grid");
    if (!type) throw std::runtime_error("no sphere_grid scene type");
    nlohmann::json defaults = nlohmann::json::object();
    for (const auto& p : type->params) defaults[p.name] = p.default_value;
    Workload out;
    out.scene = type->build(sb::Params(defaults));
    out.gbuffer = sb::reference::trace_gbuffer(out.scene, 800, 600);
    for (size_t i = 0; i < out.gbuffer.positions.pixel_count(); ++i)
      out.covered += out.gbuffer.positions.data[i * 4 + 3] > 0.5f;
    return out;
  }();
  return w;
}

void BM_Reference(benchmark::State& state) {
  const Workload& w = workload();
  const sb::reference::Settings settings{int(state.range(0)), 1};
  double traced = 0;
  for (auto _ : state) {
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
  const Workload& w = workload();
  for (auto _ : state)
    benchmark::DoNotOptimize(
        sb::reference::cache_key(w.scene, w.gbuffer.positions, w.gbuffer.normals, {256, 1}));
}

BENCHMARK(BM_CacheKey)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
