// The adaptive reference's bias, measured over many seeds against the exact
// reference or a dense uniform one (reference/adaptive.h):
// - where it picks how many samples a pixel's estimate takes, that choice
//   must not bias the estimate (in adaptive version 3 and before it did:
//   stopping where the estimate's own samples happened to agree pulled values
//   towards 0 and 1, chi²/n 13-38 over the penumbra below at target 0.1);
// - where the window rule stops a pixel at an agreeing pilot, with nothing to
//   prove it, the bias and the root mean square error that stops add stay
//   within the bounds adaptive.h derives, and the pixel reports that error
//   as its standard error, not 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "reference/adaptive.h"
#include "reference/reference.h"
#include "test_scenes.h"

namespace {

using sb::reference::Result;
using sb::reference::Settings;

Settings adaptive(int spp, double target, int pilot, uint64_t seed) {
  Settings s(spp, seed);
  s.adaptive = true;
  s.pilot_spp = pilot;
  s.target_std_error = target;
  return s;
}

bool covered(const sb::core::ImageF& positions, size_t i) {
  return positions.data[i * 4 + 3] > 0.5f;
}

// Per pixel, the mean and variance of the adaptive estimate over `seeds`
// seeds.
struct OverSeeds {
  std::vector<double> mean, variance;
};

OverSeeds over_seeds(const sb::core::Scene& scene, const sb::reference::GBuffer& g, int spp,
                     double target, int pilot, int seeds) {
  const size_t n = g.positions.pixel_count();
  std::vector<double> sum(n, 0.0), sum2(n, 0.0);
  for (int seed = 1; seed <= seeds; ++seed) {
    const Result a = sb::reference::compute(scene, g.positions, g.normals,
                                            adaptive(spp, target, pilot, uint64_t(seed)));
    for (size_t i = 0; i < n; ++i) {
      sum[i] += a.visibility.data[i];
      sum2[i] += double(a.visibility.data[i]) * a.visibility.data[i];
    }
  }
  OverSeeds out{std::vector<double>(n), std::vector<double>(n)};
  for (size_t i = 0; i < n; ++i) {
    out.mean[i] = sum[i] / seeds;
    out.variance[i] = std::max(sum2[i] / seeds - out.mean[i] * out.mean[i], 0.0);
  }
  return out;
}

// A target that stops many pixels below the full count, on a penumbra the
// exact reference knows without noise: per soft pixel, z = (mean over seeds
// - exact) / its standard error. Unbiased estimates give chi²/n = mean z²
// near 1 (the 189 pixels' own sampling: about ±0.1), and no |z| beyond 5.
void expect_unbiased_below_the_full_count(int pilot) {
  const sb::core::Scene scene = sbtest::sphere_over_plane();
  const sb::reference::GBuffer g = sb::reference::trace_gbuffer(scene, 48, 36);
  Settings exact_settings;
  exact_settings.exact = true;
  const Result exact = sb::reference::compute(scene, g.positions, g.normals, exact_settings);
  constexpr int kSeeds = 120;
  const OverSeeds a = over_seeds(scene, g, 1024, 0.1, pilot, kSeeds);
  size_t soft = 0, beyond_5 = 0;
  double chi2 = 0, worst = 0;
  for (size_t i = 0; i < a.mean.size(); ++i) {
    const double e = exact.visibility.data[i];
    if (!covered(g.positions, i) || !(e > 0.01 && e < 0.99)) continue;
    ASSERT_GT(a.variance[i], 0.0) << "pixel " << i << ": the same value on every seed";
    const double z = (a.mean[i] - e) / std::sqrt(a.variance[i] / kSeeds);
    ++soft;
    chi2 += z * z;
    worst = std::max(worst, std::abs(a.mean[i] - e));
    if (std::abs(z) > 5.0) ++beyond_5;
  }
  std::printf("pilot %d, target 0.1: %zu soft px, chi2/n %.2f, worst |bias| %.4f\n", pilot, soft,
              chi2 / double(soft), worst);
  ASSERT_GT(soft, 100u);
  EXPECT_LT(chi2 / double(soft), 1.5);
  EXPECT_EQ(beyond_5, 0u);
}

TEST(ReferenceAdaptiveBias, TheLevelAnEstimateStopsAtDoesNotBiasIt) {
  expect_unbiased_below_the_full_count(16);
}

TEST(ReferenceAdaptiveBias, TheLevelAnEstimateStopsAtDoesNotBiasItFromAFourSamplePilot) {
  expect_unbiased_below_the_full_count(4);
}

// The bounds themselves: max_p p (1 - p)^n and max_p p (1 - p)^(n/2), by
// brute force over p.
TEST(ReferenceAdaptiveBias, TheStopBoundsAreTheMaximaTheyClaim) {
  for (int n : {1, 4, 16, 64, 256}) {
    double bias = 0, rms = 0;
    for (int k = 0; k <= 100000; ++k) {
      const double p = k / 100000.0;
      bias = std::max(bias, p * std::pow(1.0 - p, n));
      rms = std::max(rms, p * std::pow(1.0 - p, 0.5 * n));
    }
    EXPECT_NEAR(sb::reference::detail::stop_bias_bound(n), bias, 1e-8) << "n = " << n;
    EXPECT_NEAR(sb::reference::detail::stop_rms_bound(n), rms, 1e-8) << "n = " << n;
  }
  EXPECT_NEAR(sb::reference::detail::stop_bias_bound(4), 0.08192, 1e-5);     // (4/5)^4 / 5
  EXPECT_NEAR(sb::reference::detail::stop_rms_bound(4), 4.0 / 27.0, 1e-12);  // (2/3)^2 / 3
}

// The window's pixels around (cx, cy), cut out of a G-buffer: the reference
// of a small image is the same per pixel (its rays depend on the pixel's
// position, normal and index in the image, which the seed stands in for).
sb::core::ImageF crop(const sb::core::ImageF& img, int cx, int cy, int half) {
  const int side = 2 * half + 1;
  sb::core::ImageF out(side, side, img.channels, 0.0f);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x)
      for (int c = 0; c < img.channels; ++c)
        out.data[(size_t(y) * size_t(side) + size_t(x)) * size_t(img.channels) + size_t(c)] =
            img.data[(size_t(cy - half + y) * size_t(img.width) + size_t(cx - half + x)) *
                         size_t(img.channels) +
                     size_t(c)];
  return out;
}

// A speck just above the ground hides about a quarter of a segment light
// (no proofs there: the window rule) from one pixel's point and nothing from
// its neighbours, so that pixel's 4-sample pilot often sees the whole light
// lit, as every pilot in its window does, and it stops at 1. Over 400 seeds:
// the stops report stop_rms_bound(4) as their standard error; the pixel's
// bias is within stop_bias_bound(4), and the root mean square error its stops
// add within stop_rms_bound(4) (this speck makes both bounds nearly tight).
TEST(ReferenceAdaptiveBias, AWindowStopReportsAndStaysWithinItsBounds) {
  sb::core::Scene scene = sbtest::sphere_over_plane();
  scene.meshes.resize(1);  // the ground alone
  scene.light.half_v = {0, 0, 0};
  const sb::reference::GBuffer plain = sb::reference::trace_gbuffer(scene, 96, 72);
  const int px = 60, py = 40, half = 4;
  const size_t pix = size_t(py) * 96 + size_t(px);
  ASSERT_TRUE(covered(plain.positions, pix));
  // The triangle from the point to the segment is about 0.02 long where the
  // speck is: a quarter of that, and 0.008 across it.
  scene.meshes.push_back(
      sbtest::speck_over(scene, sbtest::position_at(plain.positions, pix), 0.0025f, 0.004f));
  const sb::reference::GBuffer full_image = sb::reference::trace_gbuffer(scene, 96, 72);
  sb::reference::GBuffer g{crop(full_image.positions, px, py, half),
                           crop(full_image.normals, px, py, half)};
  const size_t centre = size_t(half) * size_t(2 * half + 1) + size_t(half);
  const Result dense = sb::reference::compute(scene, g.positions, g.normals, {16384, 7});
  const double v = dense.visibility.data[centre];
  ASSERT_GT(v, 0.6);
  ASSERT_LT(v, 0.9);
  for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
    if (i == centre) continue;
    ASSERT_EQ(dense.visibility.data[i], 1.0f) << "the speck shades pixel " << i;
  }

  const double bias_bound = sb::reference::detail::stop_bias_bound(4);
  const double rms_bound = sb::reference::detail::stop_rms_bound(4);
  constexpr int kSeeds = 400;
  int stops = 0;
  double sum = 0, sum2 = 0, stop_err2 = 0;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const Result a = sb::reference::compute(scene, g.positions, g.normals,
                                            adaptive(256, 0.02, 4, uint64_t(seed)));
    const double av = a.visibility.data[centre];
    sum += av;
    sum2 += av * av;
    if (a.samples.data[centre] == 4.0f) {
      ++stops;
      EXPECT_EQ(av, 1.0) << "seed " << seed;
      // No spread to estimate: σ 0, and the bound beside it.
      EXPECT_EQ(a.std_error.data[centre], 0.0f) << "seed " << seed;
      EXPECT_FLOAT_EQ(a.stop_bound.data[centre], float(rms_bound)) << "seed " << seed;
      stop_err2 += (av - v) * (av - v);
    } else {
      EXPECT_EQ(a.samples.data[centre], 4.0f + 256.0f) << "seed " << seed;
    }
    // Refined, the centre turns out mixed and sends its 24 window
    // neighbours to the full count as well.
    EXPECT_EQ(a.unproven_stops, a.samples.data[centre] == 4.0f ? 81 : 81 - 25) << "seed " << seed;
    EXPECT_EQ(a.stop_bias_bound, bias_bound) << "seed " << seed;
  }
  const double mean = sum / kSeeds;
  const double se = std::sqrt(std::max(sum2 / kSeeds - mean * mean, 0.0) / kSeeds);
  const double stop_rms = std::sqrt(stop_err2 / kSeeds);
  std::printf(
      "V %.4f: %d of %d seeds stopped at the pilot; bias %.4f (bound %.4f, se %.4f), stops' RMS "
      "error %.4f (bound %.4f)\n",
      v, stops, kSeeds, mean - v, bias_bound, se, stop_rms, rms_bound);
  ASSERT_GT(stops, kSeeds / 10) << "the window rule was not exercised";
  EXPECT_LE(mean - v, bias_bound + 3.0 * se);
  EXPECT_GE(mean - v, -3.0 * se);  // a stop can only call the pixel lighter
  // The stops' squared errors are (1 - v)² each: their share's binomial
  // noise over 400 seeds, three times, is the slack.
  const double q = double(stops) / kSeeds;
  EXPECT_LE(stop_rms, std::sqrt(rms_bound * rms_bound +
                                3.0 * std::sqrt(q * (1.0 - q) / kSeeds) * (1.0 - v) * (1.0 - v)));
}

}  // namespace
