#include "metrics/ssim_kernels.h"

namespace sb::metrics::detail {

namespace {

// The loops, written once and inlined into each target's function below,
// which the compiler vectorises for that target's width. The taps are the
// inner loop, unrolled, so that each output's sums stay in registers; the
// loads and stores of accumulators in memory, once per tap, were what bound
// the tap-outer loops. Every sum still starts at 0 and adds the taps in
// order, so the bits are those of the tap-outer form.
[[gnu::always_inline]] inline void vertical_body(const std::array<const float*, kSsimTaps>& rows_a,
                                                 const std::array<const float*, kSsimTaps>& rows_b,
                                                 const std::array<double, kSsimTaps>& w, size_t n,
                                                 Moments out) {
  double* __restrict oa = out.a;
  double* __restrict ob = out.b;
  double* __restrict oaa = out.aa;
  double* __restrict obb = out.bb;
  double* __restrict oab = out.ab;
  // The 22 input rows never overlap the outputs (ssim.cpp): more pointers
  // than the compiler checks for overlap at run time, so it is told.
#pragma GCC ivdep
  for (size_t i = 0; i < n; ++i) {
    double sa = 0.0, sb = 0.0, saa = 0.0, sbb = 0.0, sab = 0.0;
#pragma GCC unroll 11
    for (int t = 0; t < kSsimTaps; ++t) {
      const double va = rows_a[size_t(t)][i], vb = rows_b[size_t(t)][i];
      const double wt = w[size_t(t)];
      sa += wt * va;
      sb += wt * vb;
      saa += wt * (va * va);
      sbb += wt * (vb * vb);
      sab += wt * (va * vb);
    }
    oa[i] = sa;
    ob[i] = sb;
    oaa[i] = saa;
    obb[i] = sbb;
    oab[i] = sab;
  }
}

[[gnu::always_inline]] inline void horizontal_body(ConstMoments in, size_t stride,
                                                   const std::array<double, kSsimTaps>& w, size_t n,
                                                   double c1, double c2, double* __restrict o) {
  for (size_t i = 0; i < n; ++i) {
    double ua = 0.0, ub = 0.0, uaa = 0.0, ubb = 0.0, uab = 0.0;
#pragma GCC unroll 11
    for (int t = 0; t < kSsimTaps; ++t) {
      const size_t q = size_t(t) * stride + i;
      const double wt = w[size_t(t)];
      ua += wt * in.a[q];
      ub += wt * in.b[q];
      uaa += wt * in.aa[q];
      ubb += wt * in.bb[q];
      uab += wt * in.ab[q];
    }
    const double va = uaa - ua * ua;
    const double vb = ubb - ub * ub;
    const double cov = uab - ua * ub;
    const double num = (2 * ua * ub + c1) * (2 * cov + c2);
    const double den = (ua * ua + ub * ub + c1) * (va + vb + c2);
    o[i] = num / den;
  }
}

// Each target's copy of the two loops.
using Rows = std::array<const float*, kSsimTaps>;
using Weights = std::array<double, kSsimTaps>;

void vertical_baseline(const Rows& ra, const Rows& rb, const Weights& w, size_t n, Moments out) {
  vertical_body(ra, rb, w, n, out);
}
void horizontal_baseline(ConstMoments in, size_t stride, const Weights& w, size_t n, double c1,
                         double c2, double* out) {
  horizontal_body(in, stride, w, n, c1, c2, out);
}

// The wider copies exist on x86-64 only; elsewhere the baseline is all.
#if defined(__x86_64__)
[[gnu::target("avx2")]] void vertical_avx2(const Rows& ra, const Rows& rb, const Weights& w,
                                           size_t n, Moments out) {
  vertical_body(ra, rb, w, n, out);
}
[[gnu::target("avx512f,prefer-vector-width=512")]] void vertical_avx512(const Rows& ra,
                                                                        const Rows& rb,
                                                                        const Weights& w, size_t n,
                                                                        Moments out) {
  vertical_body(ra, rb, w, n, out);
}
[[gnu::target("avx2")]] void horizontal_avx2(ConstMoments in, size_t stride, const Weights& w,
                                             size_t n, double c1, double c2, double* out) {
  horizontal_body(in, stride, w, n, c1, c2, out);
}
[[gnu::target("avx512f,prefer-vector-width=512")]] void horizontal_avx512(
    ConstMoments in, size_t stride, const Weights& w, size_t n, double c1, double c2, double* out) {
  horizontal_body(in, stride, w, n, c1, c2, out);
}
#endif

}  // namespace

void vertical_moments(SimdPath path, const std::array<const float*, kSsimTaps>& rows_a,
                      const std::array<const float*, kSsimTaps>& rows_b,
                      const std::array<double, kSsimTaps>& w, size_t n, Moments out) {
#if defined(__x86_64__)
  if (path == SimdPath::Avx512) return vertical_avx512(rows_a, rows_b, w, n, out);
  if (path == SimdPath::Avx2) return vertical_avx2(rows_a, rows_b, w, n, out);
#endif
  (void)path;  // elsewhere every path is the baseline
  vertical_baseline(rows_a, rows_b, w, n, out);
}

void horizontal_ssim(SimdPath path, ConstMoments in, size_t stride,
                     const std::array<double, kSsimTaps>& w, size_t n, double c1, double c2,
                     double* out) {
#if defined(__x86_64__)
  if (path == SimdPath::Avx512) return horizontal_avx512(in, stride, w, n, c1, c2, out);
  if (path == SimdPath::Avx2) return horizontal_avx2(in, stride, w, n, c1, c2, out);
#endif
  (void)path;  // elsewhere every path is the baseline
  horizontal_baseline(in, stride, w, n, c1, c2, out);
}

}  // namespace sb::metrics::detail
