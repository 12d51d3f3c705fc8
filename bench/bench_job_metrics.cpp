// A job's measurement (metrics::measure: every region's error statistics,
// SSIM and FLIP of V and of the shaded image, and the shaded PNGs' FLIP) as
// the harness runs it after a job's frames: its `measure` phase.
//
// The workload is the default sphere grid at 640×480 (configs/quick.json's
// larger view), its G-buffer made by primary ray casting, the reference V
// at 16 spp and a "technique" V at 4 spp of another seed (noisy everywhere
// the light is partly seen: a worst case for the regions' own maps), each
// shaded on the CPU (grey Lambert, 0.1 ambient). Not timed: making those.
//   build/bench/bench_job_metrics
// BM_MeasureJob is a job after the first (the reference prepared);
// BM_PrepareReference what the first pays besides.
// Load-independent, for before/after: instruction counts of one measure():
//   valgrind --tool=callgrind --toggle-collect='sb::metrics::measure*'
//     build/bench/bench_job_metrics --benchmark_filter=MeasureJob/1 --benchmark_min_time=0.0001
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <glm/glm.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/params.h"
#include "core/scene_types.h"
#include "metrics/flip.h"
#include "metrics/job_metrics.h"
#include "metrics/light_horizon.h"
#include "metrics/prepared_reference.h"
#include "metrics/regions.h"
#include "reference/reference.h"

namespace {

using sb::core::ImageF;

constexpr int kWidth = 640, kHeight = 480;

ImageF shade(const ImageF& visibility, const sb::reference::GBuffer& g,
             const sb::core::AreaLight& light) {
  ImageF out(visibility.width, visibility.height, 3);
  for (std::size_t p = 0; p < visibility.pixel_count(); ++p) {
    const float* pos = &g.positions.data[p * 4];
    const float* nrm = &g.normals.data[p * 3];
    const glm::vec3 l = glm::normalize(light.center - glm::vec3(pos[0], pos[1], pos[2]));
    const float lambert = std::max(0.0f, glm::dot(glm::vec3(nrm[0], nrm[1], nrm[2]), l));
    const float v = pos[3] > 0.5f ? 0.1f + 0.9f * 0.8f * lambert * visibility.data[p] : 0.0f;
    for (int c = 0; c < 3; ++c) out.data[p * 3 + c] = v;
  }
  return out;
}

struct JobWorkload {
  ImageF visibility, shaded, ref_visibility, ref_shaded;
  sb::metrics::Regions regions;
};

const JobWorkload& job() {
  static const JobWorkload w = [] {
    const sb::core::SceneType* type = sb::core::find_scene_type("sphere_grid");
    if (!type) throw std::runtime_error("no sphere_grid scene type");
    nlohmann::json params = nlohmann::json::object();
    for (const auto& p : type->params) params[p.name] = p.default_value;
    const sb::core::Scene scene = type->build(sb::core::Params(params));
    const sb::reference::GBuffer g = sb::reference::trace_gbuffer(scene, kWidth, kHeight);
    const sb::reference::Result ref =
        sb::reference::compute(scene, g.positions, g.normals, sb::reference::Settings{16, 1});
    const sb::reference::Result noisy =
        sb::reference::compute(scene, g.positions, g.normals, sb::reference::Settings{4, 2});
    JobWorkload out;
    sb::metrics::RegionInputs in;
    in.horizon = sb::metrics::classify_light_horizon(g.positions, g.normals, scene.light);
    in.reference_penumbra = ref.penumbra;
    in.receiver.assign(g.positions.pixel_count(), 0);
    out.regions = sb::metrics::make_regions(in);
    out.ref_visibility = ref.visibility;
    out.visibility = noisy.visibility;
    sb::metrics::apply_attached_shadow(out.regions.attached, out.ref_visibility);
    sb::metrics::apply_attached_shadow(out.regions.attached, out.visibility);
    out.shaded = shade(out.visibility, g, scene.light);
    out.ref_shaded = shade(out.ref_visibility, g, scene.light);
    return out;
  }();
  return w;
}

// The number of threads from the argument (0: TBB's default); on one,
// callgrind counts all the work.
void limit_threads(const benchmark::State& state, std::optional<tbb::global_control>& threads) {
  if (state.range(0) > 0)
    threads.emplace(tbb::global_control::max_allowed_parallelism,
                    static_cast<std::size_t>(state.range(0)));
}

// A job after the first of its (scene, resolution): the reference's half
// of FLIP made already, as the harness keeps it (metrics/prepared_reference.h).
// Real time: the comparisons and FLIP run on all cores.
void BM_MeasureJob(benchmark::State& state) {
  const JobWorkload& w = job();
  std::optional<tbb::global_control> threads;
  limit_threads(state, threads);
  const sb::metrics::PreparedReference reference(w.ref_visibility, w.ref_shaded,
                                                 sb::metrics::kFlipDefaultPixelsPerDegree);
  (void)reference.flip_visibility();  // made by the first job
  for (auto _ : state) {              // NOLINT(clang-analyzer-deadcode.DeadStores)
    sb::core::ImageF flip_map;
    const auto m = sb::metrics::measure(w.visibility, w.shaded, reference, w.regions, &flip_map);
    benchmark::DoNotOptimize(m.flip_shaded);
  }
}

// What the first job pays besides: the reference's half of FLIP, made.
void BM_PrepareReference(benchmark::State& state) {
  const JobWorkload& w = job();
  std::optional<tbb::global_control> threads;
  limit_threads(state, threads);
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    const sb::metrics::PreparedReference reference(w.ref_visibility, w.ref_shaded,
                                                   sb::metrics::kFlipDefaultPixelsPerDegree);
    benchmark::DoNotOptimize(reference.flip_shaded_png().planes().data());
  }
}

}  // namespace

BENCHMARK(BM_MeasureJob)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PrepareReference)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
