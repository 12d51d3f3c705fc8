// The stability figures on constructed images with known answers: the
// flicker of a known sequence (mean, numpy-interpolated 99th percentile,
// max), zero for identical frames; and the finite-difference sensitivity of
// a function of the parameter with a known derivative.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "metrics/stability.h"

namespace sb::metrics {

using core::ImageF;

namespace {

ImageF filled(int w, int h, float v) { return ImageF(w, h, 1, v); }

TEST(StabilityMetrics, IdenticalFramesDoNotFlicker) {
  const std::vector<ImageF> frames(4, filled(8, 6, 0.25f));
  const FlickerStats f = flicker(frames);
  EXPECT_EQ(f.frames, 4);
  EXPECT_EQ(f.samples, 3u * 48u);
  EXPECT_EQ(f.mean, 0.0);
  EXPECT_EQ(f.p99, 0.0);
  EXPECT_EQ(f.max, 0.0);
}

TEST(StabilityMetrics, FlickerPoolsEveryPairOfFrames) {
  // 100 pixels; frame k holds k·(i + ½)/1000 at pixel i, so |ΔV| =
  // (i + ½)/1000 for every pair: the mean is 0.05, the max 0.0995, and
  // numpy.percentile of {0.5, ..., 99.5}/1000 (twice over) at 99 gives
  // 0.09851.
  std::vector<ImageF> frames;
  for (int k = 0; k < 3; ++k) {
    ImageF im(10, 10, 1, 0.0f);
    for (int i = 0; i < 100; ++i) im.data[size_t(i)] = float(k) * (float(i) + 0.5f) / 1000.0f;
    frames.push_back(im);
  }
  const FlickerStats f = flicker(frames);
  EXPECT_EQ(f.samples, 200u);
  EXPECT_NEAR(f.mean, 0.05, 1e-6);
  EXPECT_NEAR(f.max, 0.0995, 1e-6);
  EXPECT_NEAR(f.p99, 0.09851, 1e-6);
  // Over 0.05 for i = 50 ... 99: half of them.
  EXPECT_DOUBLE_EQ(f.frac_over_005, 0.5);
}

TEST(StabilityMetrics, FlickerHonoursTheMaskAndCountsNonFinitePairs) {
  std::vector<ImageF> frames{filled(2, 1, 0.0f), filled(2, 1, 1.0f)};
  frames[1].data[1] = std::numeric_limits<float>::quiet_NaN();
  const FlickerStats f = flicker(frames);
  EXPECT_EQ(f.samples, 1u);
  EXPECT_EQ(f.nonfinite, 1u);
  EXPECT_EQ(f.mean, 1.0);
  const std::vector<uint8_t> mask{0, 1};
  EXPECT_EQ(flicker(frames, &mask).samples, 0u);
  EXPECT_THROW(flicker({frames[0]}), std::invalid_argument);
  EXPECT_THROW(flicker({frames[0], filled(3, 1, 0.0f)}), std::invalid_argument);
}

TEST(StabilityMetrics, SensitivityMatchesAKnownDerivative) {
  // V_i(p) = clamp(0.5 + a_i (p - 2)^3 + b_i p) with dV_i/dp at p = 2 equal
  // to b_i; central differences are exact for the cubic term's odd part up
  // to a_i h², so the mean absolute derivative is mean |b_i| to O(h²).
  const int n = 64;
  const double p = 2.0, h = 1e-3;
  auto v_at = [&](double q) {
    ImageF im(n, 1, 1, 0.0f);
    for (int i = 0; i < n; ++i) {
      const double a = 0.01 * i, b = 0.002 * (i - 32);
      im.data[size_t(i)] = float(0.5 + a * std::pow(q - 2.0, 3) + b * q - b * p);
    }
    return im;
  };
  double mean_abs_b = 0.0;
  for (int i = 0; i < n; ++i) mean_abs_b += std::fabs(0.002 * (i - 32)) / n;
  const Sensitivity s = sensitivity(v_at(p + h), v_at(p - h), p, h);
  // float storage: V is rounded to 2^-24 relative, ΔV/2h to ~6e-8/2e-3.
  EXPECT_NEAR(s.dv_dp, mean_abs_b, 1e-4);
  EXPECT_NEAR(s.relative, 2.0 * mean_abs_b, 2e-4);
  EXPECT_EQ(s.step, h);
  EXPECT_THROW(sensitivity(v_at(p), v_at(p), p, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace sb::metrics
