// The shared passes on the default sphere grid (81 UV spheres of 760
// triangles over a ground plane) at 800×600, one headless OSMesa context:
// the G-buffer pass (clears, scene, every attachment), rendered once per
// (scene, resolution); the restore of its depth-stencil, which every frame
// pays whatever the technique (run/gbuffer.h); and the shading pass. Each iteration times the pass
// plus glFinish() with steady_clock, as the harness's CPU-finish brackets do (llvmpipe's
// GL_TIME_ELAPSED reads about one tile's time: docs/design.md, "Fairness rules").
//
// The harness's own records hold the figure the target is about
// (timing.shared.gbuffer against timing.frame of a hard shadow map at
// 800×600, docs/performance.md); this benchmark is the pass alone, for
// profiling it:
//   perf record -g build/bench/bench_gbuffer --benchmark_filter=GBuffer
// LP_NUM_THREADS sets llvmpipe's thread count (default: the core count).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <vector>

#include "gl/debug.h"
#include "gl/gl.h"
#include "gl/gpu_scene.h"
#include "gl_bench_main.h"
#include "reference_workload.h"
#include "run/gbuffer.h"

namespace {

constexpr int kWidth = 800, kHeight = 600;

struct Workload {
  sb::core::Scene scene;
  std::unique_ptr<sb::gl::GpuScene> gpu;
  std::unique_ptr<sb::run::FrameTargets> targets;
  glm::mat4 view_projection{1.0f};
};

Workload& workload() {
  static Workload w = [] {
    Workload out;
    out.scene = sb::bench::scene_workload("sphere_grid").scene;
    out.gpu = std::make_unique<sb::gl::GpuScene>(out.scene, std::vector<std::vector<uint32_t>>{});
    out.targets = std::make_unique<sb::run::FrameTargets>(kWidth, kHeight);
    const sb::core::Camera& c = out.scene.camera;
    out.view_projection = c.projection(float(kWidth) / float(kHeight)) * c.view();
    return out;
  }();
  return w;
}

template <typename Pass>
void time_pass(benchmark::State& state, Pass&& pass) {
  pass();  // compile and first use, untimed
  glFinish();
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    const auto t0 = std::chrono::steady_clock::now();
    pass();
    glFinish();
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  sb::gl::throw_if_errors("bench_gbuffer");
}

void BM_GBuffer(benchmark::State& state) {
  Workload& w = workload();
  time_pass(state, [&] { w.targets->render_gbuffer(*w.gpu, w.view_projection); });
  state.counters["triangles"] = double(w.scene.triangle_count());
}

void BM_GBufferRestore(benchmark::State& state) {
  Workload& w = workload();
  w.targets->render_gbuffer(*w.gpu, w.view_projection);
  time_pass(state, [&] { w.targets->restore_gbuffer(); });
}

void BM_Shading(benchmark::State& state) {
  Workload& w = workload();
  w.targets->render_gbuffer(*w.gpu, w.view_projection);
  time_pass(state, [&] { w.targets->render_shading(w.scene); });
}

BENCHMARK(BM_GBuffer)->Unit(benchmark::kMillisecond)->UseManualTime()->MinTime(2.0);
BENCHMARK(BM_GBufferRestore)->Unit(benchmark::kMillisecond)->UseManualTime()->MinTime(1.0);
BENCHMARK(BM_Shading)->Unit(benchmark::kMillisecond)->UseManualTime()->MinTime(1.0);

}  // namespace

int main(int argc, char** argv) {
  return run_gl_benchmarks(argc, argv, "bench_gbuffer", [] {
    Workload& w = workload();
    w.targets.reset();
    w.gpu.reset();
  });
}
