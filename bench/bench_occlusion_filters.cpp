// Cost of building the filtered forms of an occlusion texture
// (techniques/occlusion_texture/filter_pyramid.h) against its size, on one
// headless OSMesa context: the mip chain (glGenerateTextureMipmap), the
// N-buffers (one compute pass per level, each at full resolution) and the
// summed-area table (a row pass and a column pass), in 32- and 16-bit
// floats. Eisemann & Décoret 2008 measured the same three on a GeForce 6800
// Ultra (docs/occlusion_textures.md has both tables); compare how each grows
// per doubling of the side, not absolute times.
//
// Each iteration times build() + glFinish() with steady_clock (llvmpipe's
// GL_TIME_ELAPSED reads about one tile's time: docs/design.md, "Fairness rules"), on an RGBA8
// texture of random binary texels (the pyramids' cost does not depend on the data). A subset:
// build/bench/bench_occlusion_filters --benchmark_filter='BM_Filter/sat/'
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdint>
#include <random>
#include <vector>

#include "gl/debug.h"
#include "gl/gl.h"
#include "gl_bench_main.h"
#include "occlusion_texture/filter_pyramid.h"

namespace {

using sb::techniques::occlusion_texture::Filter;
using sb::techniques::occlusion_texture::FilterPyramid;

void BM_Filter(benchmark::State& state, Filter filter, bool half) {
  const int size = int(state.range(0));
  FilterPyramid pyramid(filter, size, half);
  std::mt19937 rng(1);
  std::vector<uint8_t> texels(size_t(size) * size_t(size) * 4);
  for (uint8_t& t : texels) t = rng() % 3 == 0 ? 255 : 0;
  glTextureSubImage2D(pyramid.source(), 0, 0, 0, size, size, GL_RGBA, GL_UNSIGNED_BYTE,
                      texels.data());
  pyramid.build();  // compiles the programs' variants before timing
  glFinish();
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): benchmark's idiom
    const auto start = std::chrono::steady_clock::now();
    pyramid.build();
    glFinish();
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  sb::gl::throw_if_errors("bench_occlusion_filters");
  state.counters["Mtexels/s"] = benchmark::Counter(double(size) * double(size) / 1e6,
                                                   benchmark::Counter::kIsIterationInvariantRate);
}

void sizes(benchmark::internal::Benchmark* b) {
  b->ArgNames({"size"})->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.5);
  for (int size : {256, 512, 1024, 2048}) b->Arg(size);
}

BENCHMARK_CAPTURE(BM_Filter, mipmap, Filter::Mipmap, false)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Filter, nbuffers, Filter::NBuffers, false)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Filter, sat, Filter::Sat, false)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Filter, sat_fp16, Filter::Sat, true)->Apply(sizes);

}  // namespace

int main(int argc, char** argv) { return run_gl_benchmarks(argc, argv, "bench_occlusion_filters"); }
