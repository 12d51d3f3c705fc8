#pragma once
// SSIM's two inner loops (ssim.cpp), compiled three times: for baseline
// x86-64 (SSE2, two doubles a vector), AVX2 (four) and AVX-512 (eight), and
// picked at run time for the CPU at hand. The build targets baseline x86-64,
// so without this the filter ran two doubles wide on every machine.
//
// All three do the same IEEE operations in the same order on every element
// (no fused multiply-add: the file is built with -ffp-contract=off), so they
// give the same bits; tests/metrics/test_ssim_kernels.cpp checks that on
// every path the CPU can run.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"
#include "metrics/simd_path.h"

namespace sb::metrics::detail {

// metrics::ssim() and ssim_map() on a given path (they take the widest).
std::vector<double> ssim_on(SimdPath path, const core::ImageF& a, const core::ImageF& b,
                            double data_range,
                            const std::vector<const std::vector<uint8_t>*>& masks);
core::ImageF ssim_map_on(SimdPath path, const core::ImageF& a, const core::ImageF& b,
                         double data_range);

inline constexpr int kSsimTaps = 11;

// The vertical pass over one chunk of n values of a row: for each tap t,
// rows_a[t][i] and rows_b[t][i] (i < n) weighted by w[t] are summed into
// the five moments a, b, a², b², ab.
struct Moments {
  double *a, *b, *aa, *bb, *ab;
};
void vertical_moments(SimdPath path, const std::array<const float*, kSsimTaps>& rows_a,
                      const std::array<const float*, kSsimTaps>& rows_b,
                      const std::array<double, kSsimTaps>& w, size_t n, Moments out);

// The horizontal pass and the SSIM formula over one chunk of n outputs:
// output i sums tap t's moments at in.x[i + t * stride] weighted by w[t],
// then
//   ((2 μa μb + c1)(2 cov + c2)) / ((μa² + μb² + c1)(σa² + σb² + c2)).
struct ConstMoments {
  const double *a, *b, *aa, *bb, *ab;
};
void horizontal_ssim(SimdPath path, ConstMoments in, size_t stride,
                     const std::array<double, kSsimTaps>& w, size_t n, double c1, double c2,
                     double* out);

}  // namespace sb::metrics::detail
