// Throughput of the image metrics on a 1920x1080 frame: compare() (all
// figures, SSIM included) and ssim() alone, 1 and 3 channels.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "metrics/metrics.h"

namespace {

constexpr int kW = 1920, kH = 1080;

// A shadow-like pair: smooth visibility with a soft edge, and a noisy,
// slightly shifted estimate of it.
void make_pair(int channels, sb::ImageF& test, sb::ImageF& ref) {
  ref = sb::ImageF(kW, kH, channels);
  test = sb::ImageF(kW, kH, channels);
  std::mt19937 rng(42);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      for (int c = 0; c < channels; ++c) {
        const float d = 0.01f * static_cast<float>(x - kW / 2 + (y % 200) - 100 + 7 * c);
        const float v = 1.0f / (1.0f + std::exp(-d));
        const float n = static_cast<float>(rng() >> 8) * (1.0f / 16777216.0f) - 0.5f;
        ref.at(x, y, c) = v;
        test.at(x, y, c) = v + 0.05f * n;
      }
    }
  }
}

void BM_Compare(benchmark::State& state) {
  sb::ImageF test, ref;
  make_pair(static_cast<int>(state.range(0)), test, ref);
  for (auto _ : state) {
    sb::metrics::ErrorStats s = sb::metrics::compare(test, ref);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations() * int64_t{kW} * kH);
}

void BM_Ssim(benchmark::State& state) {
  sb::ImageF test, ref;
  make_pair(static_cast<int>(state.range(0)), test, ref);
  for (auto _ : state) {
    double s = sb::metrics::ssim(test, ref);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations() * int64_t{kW} * kH);
}

// Items are pixels; the argument is the channel count. Real time, since the
// SSIM filter runs on all cores.
BENCHMARK(BM_Compare)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Ssim)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
