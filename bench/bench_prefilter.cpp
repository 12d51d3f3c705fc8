// Cost of the separable prefilter of the filterable shadow maps
// (sb::techniques::SeparableFilter: VSM, ESM, EVSM, MSM, CSM) against map size,
// kernel side k and channel count, on one headless OSMesa context.
//
// Arguments: size (map side, texels) × ch (1 = R32F as ESM, 2 = RG32F as VSM,
// 4 = RGBA32F as MSM / 4-component EVSM) × k (taps per pass). One array
// layer: CSM's M Fourier terms and EVSM/MSM stacks of several layers cost
// that many times one layer. `linear` is the weighted sum every family uses;
// `log_sum_exp` is ESM's log-space filter (R32F only; it reads each tap twice
// and takes an exp per tap). The weights are Gaussian: box weights run the
// same shader with other uniform values, so the single `box` case is only
// there to show that the shape does not change the cost.
//
// Each iteration times apply() + glFinish() with steady_clock (llvmpipe's
// GL_TIME_ELAPSED reads about one tile's time: docs/design.md, "Fairness rules"). The filter works
// in place, so the data gets smoother from one iteration to the next; the shader has no
// data-dependent branch, so the cost does not change. Per apply and over the
// measured time, "Mtaps/s" counts size²·2·k texel reads and "Mtexel-taps/s"
// size²·2·k·ch channel reads (the shader works on vec4 whatever the format).
//
// The whole run takes 2 min 10 s on an idle 2-core machine (llvmpipe's 2
// threads), twice that while other builds share the cores. A subset:
//   build/bench/bench_prefilter --benchmark_filter='linear/size:1024/'
//   build/bench/bench_prefilter --benchmark_filter='size:(512|2048)/ch:2/k:(5|9)/'
//   build/bench/bench_prefilter --benchmark_filter='log_sum_exp|box'
//   build/bench/bench_prefilter --benchmark_filter='-size:4096'   (all but 4096²)
// (names end in /min_time:0.500/manual_time or /iterations:3/manual_time, so
// end a pattern with '/', not '$'; --benchmark_list_tests lists them).
// LP_NUM_THREADS sets llvmpipe's thread count (default: the core count).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/kernel.h"
#include "common/separable_filter.h"
#include "gl/context.h"
#include "gl/debug.h"
#include "gl/gl.h"
#include "gl_bench_main.h"

namespace {

using sb::techniques::KernelShape;
using sb::techniques::SeparableFilter;

struct Variant {
  SeparableFilter::Mode mode;
  KernelShape shape;
};

constexpr float kEsmExponent = 80.0f;  // esm's default exponent

GLenum internal_format(int channels) {
  return channels == 1 ? GL_R32F : channels == 2 ? GL_RG32F : GL_RGBA32F;
}

GLenum pixel_format(int channels) {
  return channels == 1 ? GL_RED : channels == 2 ? GL_RG : GL_RGBA;
}

const char* format_label(int channels) {
  return channels == 1 ? "R32F (ESM)" : channels == 2 ? "RG32F (VSM)" : "RGBA32F (MSM/EVSM)";
}

// Moments z, z², z³, z⁴ of a depth-like field in [0.25, 0.75]: smooth waves
// plus per-texel noise, so the map is neither constant nor trivially smooth.
std::vector<float> moment_data(int size, int channels) {
  std::vector<float> out(size_t(size) * size_t(size) * size_t(channels));
  size_t i = 0;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      uint32_t h = (uint32_t(x) * 0x9E3779B1u) ^ (uint32_t(y) * 0x85EBCA77u);
      h ^= h >> 15;
      h *= 0x2C1B3C6Du;
      h ^= h >> 13;
      const float noise = float(h >> 8) * (1.0f / 16777216.0f) - 0.5f;
      const float z =
          0.5f + 0.2f * std::sin(0.05f * float(x)) * std::cos(0.03f * float(y)) + 0.05f * noise;
      float moment = z;
      for (int c = 0; c < channels; ++c, moment *= z) out[i++] = moment;
    }
  }
  return out;
}

// The map and filter of the benchmark that runs now. Google Benchmark calls a
// benchmark function once per trial iteration count, so they are kept while
// the arguments stay the same, and the map while size and channels do.
struct Fixture {
  int size = 0;
  int channels = 0;
  sb::gl::Texture map;
  int k = 0;
  std::optional<Variant> variant;
  std::optional<SeparableFilter> filter;

  void prepare(int new_size, int new_channels, int new_k, Variant v) {
    if (new_size != size || new_channels != channels) {
      filter.reset();
      map = sb::techniques::make_array_texture(internal_format(new_channels), new_size, 1);
      const std::vector<float> data = moment_data(new_size, new_channels);
      glTextureSubImage3D(map.get(), 0, 0, 0, 0, new_size, new_size, 1, pixel_format(new_channels),
                          GL_FLOAT, data.data());
      size = new_size;
      channels = new_channels;
    }
    if (!filter || new_k != k || variant->mode != v.mode || variant->shape != v.shape) {
      filter.reset();
      filter.emplace(map.get(), internal_format(channels), size, 1,
                     sb::techniques::kernel_weights(v.shape, new_k, 0.0f), v.mode, kEsmExponent);
      k = new_k;
      variant = v;
      // The first draw compiles llvmpipe's shader variant: keep it untimed.
      filter->apply();
    }
    glFinish();
    sb::gl::throw_if_errors("preparing the prefilter benchmark");
  }
};

std::unique_ptr<Fixture> g_fixture;

void BM_Prefilter(benchmark::State& state, Variant variant) {
  const int size = int(state.range(0));
  const int channels = int(state.range(1));
  const int k = int(state.range(2));
  try {
    if (!g_fixture) g_fixture = std::make_unique<Fixture>();
    g_fixture->prepare(size, channels, k, variant);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  const SeparableFilter& filter = *g_fixture->filter;
  double measured = 0.0;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): benchmark's idiom
    const auto start = std::chrono::steady_clock::now();
    filter.apply();
    glFinish();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.SetIterationTime(seconds);
    measured += seconds;
  }
  const double taps = double(size) * double(size) * 2.0 * double(k);
  const double per_second = double(state.iterations()) / measured * 1e-6;
  state.counters["Mtaps/s"] = taps * per_second;
  state.counters["Mtexel-taps/s"] = taps * double(channels) * per_second;
  state.SetLabel(format_label(channels));
}

// Registered in this order: linear, log_sum_exp, box. Up to 2048² a minimum
// time of 0.5 s gives each case 2 to about 100 iterations; a 4096² apply
// takes up to 1.2 s (1.6 s in log_sum_exp), so those run exactly 3
// iterations. k varies fastest, so a map is filled once for all its kernels.
void register_benchmarks() {
  const Variant linear{SeparableFilter::Mode::Linear, KernelShape::Gauss};
  const Variant log_sum_exp{SeparableFilter::Mode::LogSumExp, KernelShape::Gauss};
  const struct {
    const char* name;
    Variant variant;
    std::vector<int> sizes, channels, ks;
  } families[] = {
      {"linear", linear, {512, 1024, 2048}, {1, 2, 4}, {3, 5, 9, 13, 19}},
      {"linear", linear, {4096}, {1, 2, 4}, {3, 5, 9, 13, 19}},
      {"log_sum_exp", log_sum_exp, {512, 1024, 2048}, {1}, {3, 5, 9, 13, 19}},
      {"log_sum_exp", log_sum_exp, {4096}, {1}, {3, 5, 9, 13, 19}},
      {"box", {SeparableFilter::Mode::Linear, KernelShape::Box}, {2048}, {2}, {9}},
  };
  for (const auto& f : families) {
    auto* b = benchmark::RegisterBenchmark((std::string("BM_Prefilter/") + f.name).c_str(),
                                           BM_Prefilter, f.variant);
    b->ArgNames({"size", "ch", "k"})->UseManualTime()->Unit(benchmark::kMillisecond);
    for (int size : f.sizes)
      for (int ch : f.channels)
        for (int k : f.ks) b->Args({size, ch, k});
    if (f.sizes.front() >= 4096)
      b->Iterations(3);
    else
      b->MinTime(0.5);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_benchmarks();
  return run_gl_benchmarks(argc, argv, "bench_prefilter", [] { g_fixture.reset(); });
}
