// The Monte Carlo reference's σ and stop bounds, and its penumbra, against
// the exact reference (reference.h):
//  - no estimate strictly between 0 and 1 reports σ = 0, and the share of
//    such estimates more than 3σ from the exact V is near a normal
//    distribution's 0.27 %, for the uniform and the adaptive reference;
//  - a pixel whose samples all agreed reports σ = 0 and a stop bound beside
//    it, and mean_std_error is the mean σ over the estimates only;
//  - the penumbra does not move with the sample count: at 64 and at 1024
//    spp it is the exact reference's to within a few pixels, where the soft
//    estimates of 64 spp miss a tenth of it.
// Sphere grid and a jeep at 160×120, G-buffers made by primary rays.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "../common/scene_of_type.h"
#include "reference/reference.h"

// Named, not anonymous: the unity build puts other files' kWidth and
// covered() in the same translation unit.
namespace honest_sigma {

using sb::core::Scene;
using sb::reference::GBuffer;
using sb::reference::Result;
using sb::reference::Settings;

constexpr int kWidth = 160, kHeight = 120;

bool covered(const GBuffer& g, size_t i) { return g.positions.data[i * 4 + 3] > 0.5f; }

Settings monte_carlo(int spp, bool adaptive = false) {
  Settings s;
  s.spp = spp;
  s.seed = 1;
  s.adaptive = adaptive;
  s.pilot_spp = 16;
  s.target_std_error = 0.01;
  return s;
}

Result exact_of(const Scene& scene, const GBuffer& g) {
  Settings s;
  s.exact = true;
  Result r = sb::reference::compute(scene, g.positions, g.normals, s);
  if (r.method != sb::reference::kExactMethod)
    throw std::runtime_error("no exact reference: " + r.exact_fallback);
  return r;
}

// σ against the exact V over the estimates strictly between 0 and 1.
struct SigmaCheck {
  size_t estimates = 0, zero_sigma = 0, beyond_3_sigma = 0;
  size_t stops = 0, stops_with_sigma = 0, stops_without_bound = 0;
  double stop_abs_error = 0.0, stop_bound = 0.0, sigma_sum = 0.0;
  double error2 = 0.0, sigma2 = 0.0;  // over the estimates
};

SigmaCheck check_sigma(const GBuffer& g, const Result& mc, const Result& exact) {
  SigmaCheck c;
  for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
    if (!covered(g, i)) continue;
    const double v = mc.visibility.data[i], sigma = mc.std_error.data[i];
    const double error = std::abs(v - double(exact.visibility.data[i]));
    if (v > 0.0 && v < 1.0) {
      ++c.estimates;
      c.sigma_sum += sigma;
      c.zero_sigma += sigma == 0.0;
      c.beyond_3_sigma += error > 3.0 * sigma;
      c.error2 += error * error;
      c.sigma2 += sigma * sigma;
    } else if (mc.stop_bound.data[i] > 0.0f) {
      ++c.stops;
      c.stops_with_sigma += sigma != 0.0;
      c.stop_abs_error += error;
      c.stop_bound += mc.stop_bound.data[i];
    } else {
      c.stops_without_bound += 1;  // proven: the exact V must agree
    }
  }
  return c;
}

// A normal σ puts 0.27 % beyond 3σ. The collapsed-strata σ is conservative
// in the mean (reference.h), but a 0/1 integrand's error has heavier tails
// near an umbra's or a lit region's edge (one sample's weight against a
// small σ): the allowance is 1 %, under the 2.6-6.8 % beyond 3σ measured
// here while estimates whose pairs all agreed reported σ = 0.
constexpr double kBeyond3SigmaShare = 0.01;

void expect_honest(const std::string& label, const Scene& scene, bool adaptive) {
  const GBuffer g = sb::reference::trace_gbuffer(scene, kWidth, kHeight);
  const Result exact = exact_of(scene, g);
  const Result mc =
      sb::reference::compute(scene, g.positions, g.normals, monte_carlo(256, adaptive));
  const SigmaCheck c = check_sigma(g, mc, exact);
  const double share = double(c.beyond_3_sigma) / double(c.estimates);
  const double true_over_stated = std::sqrt(c.error2 / c.sigma2);
  std::printf(
      "%s: %zu estimates (%zu with sigma 0), %.3f %% beyond 3 sigma, RMS error / RMS sigma "
      "%.2f; %zu stops, mean |error| %.2e, mean bound %.2e\n",
      label.c_str(), c.estimates, c.zero_sigma, 100.0 * share, true_over_stated, c.stops,
      c.stops ? c.stop_abs_error / double(c.stops) : 0.0,
      c.stops ? c.stop_bound / double(c.stops) : 0.0);
  ASSERT_GT(c.estimates, 500u) << label;
  EXPECT_EQ(c.zero_sigma, 0u) << label;
  EXPECT_LE(share, kBeyond3SigmaShare) << label;
  // Conservative, as the collapsed-strata estimate is (reference.h), but the
  // right size: neither far below the true error nor far above it.
  EXPECT_GT(true_over_stated, 0.4) << label;
  EXPECT_LT(true_over_stated, 1.2) << label;
  // Agreeing samples: σ 0, their bound beside it, and on average no more
  // off than the bound allows.
  EXPECT_EQ(c.stops_with_sigma, 0u) << label;
  ASSERT_GT(c.stops, 0u) << label;
  EXPECT_LE(c.stop_abs_error, c.stop_bound) << label;
  EXPECT_EQ(mc.stopped_pixels, int64_t(c.stops)) << label;
  EXPECT_EQ(mc.estimate_pixels, int64_t(c.estimates)) << label;
  EXPECT_NEAR(mc.mean_std_error, c.sigma_sum / double(c.estimates), 1e-9) << label;
}

TEST(ReferenceSigma, UniformEstimatesAreWithinThreeSigmaOfTheExactReference) {
  expect_honest("sphere grid, uniform", sb::test::scene_of_type("sphere_grid", {{"grid", 3}}),
                false);
  expect_honest("jeep, uniform", sb::test::scene_of_type("jeep", {}), false);
}

TEST(ReferenceSigma, AdaptiveEstimatesAreWithinThreeSigmaOfTheExactReference) {
  expect_honest("sphere grid, adaptive", sb::test::scene_of_type("sphere_grid", {{"grid", 3}}),
                true);
  expect_honest("jeep, adaptive", sb::test::scene_of_type("jeep", {}), true);
}

// A segment light: the adaptive reference has no proofs there, and its
// window rule stops most lit and umbra pixels at their 16-sample pilot.
// Those stops carry their bound, not a σ, so mean_std_error is the
// estimates' alone (it read 0.086 when each stop's bound counted as σ).
TEST(ReferenceSigma, WindowRuleStopsReportTheirBoundBesideSigma) {
  Scene scene = sb::test::scene_of_type("sphere_grid", {{"grid", 3}});
  scene.light.half_v = glm::vec3(0.0f);  // a segment along half_u
  ASSERT_TRUE(scene.light.is_segment());
  const GBuffer g = sb::reference::trace_gbuffer(scene, kWidth, kHeight);
  const Result exact = exact_of(scene, g);
  const Result mc = sb::reference::compute(scene, g.positions, g.normals, monte_carlo(256, true));
  ASSERT_GT(mc.unproven_stops, 1000);
  const SigmaCheck c = check_sigma(g, mc, exact);
  std::printf("segment, adaptive: %lld window stops, mean sigma %.4f, mean bound %.4f\n",
              static_cast<long long>(mc.unproven_stops), mc.mean_std_error, mc.mean_stop_bound);
  EXPECT_EQ(c.stops_with_sigma, 0u);
  EXPECT_EQ(c.zero_sigma, 0u);
  EXPECT_NEAR(mc.mean_std_error, c.sigma_sum / double(c.estimates), 1e-9);
  EXPECT_LT(mc.mean_std_error, 0.03);  // the target is 0.01; a stop's bound is 0.13
  EXPECT_LE(c.stop_abs_error, c.stop_bound);
}

// Pixels in one region and not the other.
size_t differ(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += (a[i] != 0) != (b[i] != 0);
  return n;
}

// At most this many pixels a region may differ from the exact one's: rays
// that graze an edge, where the sampled and the exact geometry part by
// float rounding.
constexpr size_t kRegionSlack = 8;

TEST(ReferencePenumbra, TheRegionDoesNotMoveWithTheSampleCount) {
  const Scene scene = sb::test::scene_of_type("sphere_grid", {{"grid", 3}});
  const GBuffer g = sb::reference::trace_gbuffer(scene, kWidth, kHeight);
  const Result exact = exact_of(scene, g);
  const Result low = sb::reference::compute(scene, g.positions, g.normals, monte_carlo(64));
  const Result high = sb::reference::compute(scene, g.positions, g.normals, monte_carlo(1024));
  EXPECT_EQ(exact.penumbra_source, sb::reference::kPenumbraExact);
  EXPECT_EQ(low.penumbra_source, sb::reference::kPenumbraExact);
  size_t truth = 0, soft_64 = 0, missed_by_soft_64 = 0;
  for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
    const float v = exact.visibility.data[i];
    const bool soft = covered(g, i) && v > 1e-6f && v < 1.0f - 1e-6f;
    EXPECT_EQ(exact.penumbra[i] != 0, soft) << "pixel " << i;
    truth += soft;
    const bool estimate_soft = low.visibility.data[i] > 0.0f && low.visibility.data[i] < 1.0f;
    soft_64 += estimate_soft;
    missed_by_soft_64 += soft && !estimate_soft;
  }
  const size_t d_low = differ(low.penumbra, exact.penumbra);
  const size_t d_high = differ(high.penumbra, exact.penumbra);
  std::printf(
      "penumbra: exact %zu px; 64 spp differs by %zu, 1024 spp by %zu; the soft estimates of "
      "64 spp (%zu px) miss %zu\n",
      truth, d_low, d_high, soft_64, missed_by_soft_64);
  ASSERT_GT(truth, 300u);
  EXPECT_LE(d_low, kRegionSlack);
  EXPECT_LE(d_high, kRegionSlack);
  EXPECT_LE(differ(low.penumbra, high.penumbra), kRegionSlack);
  // The test tells: the region the soft estimates gave, before, fails it.
  EXPECT_GT(missed_by_soft_64, 10 * kRegionSlack);
}

// Where the scene has no exact form (analytic casters), the region is the
// soft estimates, and says so.
TEST(ReferencePenumbra, WithoutAnExactFormTheRegionIsTheSoftEstimatesAndSaysSo) {
  Scene scene = sb::test::scene_of_type("sphere_grid", {{"grid", 2}, {"analytic", true}});
  const GBuffer g = sb::reference::trace_gbuffer(scene, 80, 60);
  const Result mc = sb::reference::compute(scene, g.positions, g.normals, monte_carlo(64));
  EXPECT_EQ(mc.penumbra_source, sb::reference::kPenumbraSampled);
  for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
    const float v = mc.visibility.data[i];
    EXPECT_EQ(mc.penumbra[i] != 0, v > 0.0f && v < 1.0f) << "pixel " << i;
  }
}

}  // namespace honest_sigma
