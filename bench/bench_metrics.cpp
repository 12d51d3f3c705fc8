// Throughput of the image metrics on a 1920x1080 frame: compare() (all
// figures, SSIM included) with one mask and with seven, as a job's
// visibility is measured, and ssim() alone, 1 and 3 channels; and SSIM on
// each of its vector widths (metrics/ssim_kernels.h) that this CPU runs,
// 3 channels: BM_SsimOnPath/0 baseline (SSE2), /1 AVX2, /2 AVX-512; and
// FLIP (metrics/flip.h) at its default 67 pixels per degree, RGB and grey,
// and RGB on each vector width: BM_FlipOnPath/0 baseline, /1 AVX2, /2 AVX-512.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "metrics/flip.h"
#include "metrics/metrics.h"
#include "metrics/ssim_kernels.h"

namespace {

constexpr int kW = 1920, kH = 1080;
constexpr int kHalfW = kW / 2;

// A shadow-like pair: smooth visibility with a soft edge, and a noisy,
// slightly shifted estimate of it.
void make_pair(int channels, sb::core::ImageF& test, sb::core::ImageF& ref) {
  ref = sb::core::ImageF(kW, kH, channels);
  test = sb::core::ImageF(kW, kH, channels);
  std::mt19937 rng(42);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      for (int c = 0; c < channels; ++c) {
        const float d = 0.01f * static_cast<float>(x - kHalfW + (y % 200) - 100 + 7 * c);
        const float v = 1.0f / (1.0f + std::exp(-d));
        const float n = static_cast<float>(rng() >> 8) * (1.0f / 16777216.0f) - 0.5f;
        ref.at(x, y, c) = v;
        test.at(x, y, c) = v + 0.05f * n;
      }
    }
  }
}

void BM_Compare(benchmark::State& state) {
  sb::core::ImageF test, ref;
  make_pair(static_cast<int>(state.range(0)), test, ref);
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    sb::metrics::ErrorStats s = sb::metrics::compare(test, ref);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations() * int64_t{kW} * kH);
}

// As a job measures its visibility: seven masks (every pixel, the measured
// ones, the penumbra, the soft union, the distance thirds) in one call.
void BM_CompareSevenMasks(benchmark::State& state) {
  sb::core::ImageF test, ref;
  make_pair(static_cast<int>(state.range(0)), test, ref);
  std::vector<std::vector<uint8_t>> masks(6, std::vector<uint8_t>(size_t(kW) * kH));
  // Regions, as a frame's are: blocks of a few dozen pixels.
  for (size_t i = 0; i < masks[0].size(); ++i)
    for (size_t m = 0; m < masks.size(); ++m)
      masks[m][i] = (i % kW / (37 + m) + i / kW / (23 + m)) % (m + 2) != 0;
  std::vector<const std::vector<uint8_t>*> all = {nullptr};
  for (const auto& m : masks) all.push_back(&m);
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    std::vector<sb::metrics::ErrorStats> s = sb::metrics::compare(test, ref, all);
    benchmark::DoNotOptimize(s.data());
  }
  state.SetItemsProcessed(state.iterations() * int64_t{kW} * kH);
}

void BM_Ssim(benchmark::State& state) {
  sb::core::ImageF test, ref;
  make_pair(static_cast<int>(state.range(0)), test, ref);
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    double s = sb::metrics::ssim(test, ref);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations() * int64_t{kW} * kH);
}

// The vector width the benchmark's argument names, with the RGB pair to
// measure on it; false (the benchmark skipped, saying why) where this CPU
// does not run it.
bool on_path(benchmark::State& state, sb::metrics::detail::SimdPath& path, sb::core::ImageF& test,
             sb::core::ImageF& ref) {
  path = static_cast<sb::metrics::detail::SimdPath>(state.range(0));
  if (!sb::metrics::detail::runs_here(path)) {
    state.SkipWithError(("this CPU has no " + sb::metrics::detail::to_string(path)).c_str());
    return false;
  }
  make_pair(3, test, ref);
  state.SetLabel(sb::metrics::detail::to_string(path));
  return true;
}

void BM_SsimOnPath(benchmark::State& state) {
  sb::metrics::detail::SimdPath path{};
  sb::core::ImageF test, ref;
  if (!on_path(state, path, test, ref)) return;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores)
    std::vector<double> s = sb::metrics::detail::ssim_on(path, test, ref, 1.0, {nullptr});
    benchmark::DoNotOptimize(s.data());
  }
  state.SetItemsProcessed(state.iterations() * int64_t{kW} * kH);
}

// The argument is the channel count. Real time, since FLIP runs on all cores.
void BM_Flip(benchmark::State& state) {
  sb::core::ImageF test, ref;
  make_pair(static_cast<int>(state.range(0)), test, ref);
  for (auto _ : state) benchmark::DoNotOptimize(sb::metrics::flip(ref, test).mean);
}

void BM_FlipOnPath(benchmark::State& state) {
  sb::metrics::detail::SimdPath path{};
  sb::core::ImageF test, ref;
  if (!on_path(state, path, test, ref)) return;
  for (auto _ : state) benchmark::DoNotOptimize(sb::metrics::detail::flip_on(path, ref, test).mean);
}

BENCHMARK(BM_Compare)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CompareSevenMasks)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Ssim)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Flip)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SsimOnPath)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FlipOnPath)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
