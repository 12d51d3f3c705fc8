// The adaptive Monte Carlo reference (reference/adaptive.h) against the
// uniform reference at its full sample count and against the exact
// reference, on the sphere grid, a jeep and foliage, at G-buffers made by
// primary rays. The full-count uniform reference is the truth the adaptive
// one must not stray from by more than its stated noise; the exact one is
// the truth both estimate.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "../common/scene_of_type.h"
#include "reference/adaptive.h"
#include "reference/reference.h"
#include "test_scenes.h"

namespace {

using sb::reference::Result;
using sb::reference::Settings;

constexpr int kWidth = 160, kHeight = 120;

Settings adaptive(int spp, double target, int pilot = 16) {
  Settings s(spp, 1);
  s.adaptive = true;
  s.pilot_spp = pilot;
  s.target_std_error = target;
  return s;
}

bool covered(const sb::reference::GBuffer& g, size_t i) {
  return g.positions.data[i * 4 + 3] > 0.5f;
}

// What the comparison with the full-count reference found.
struct Agreement {
  size_t covered = 0, penumbra = 0;  // the full reference's 0 < V < 1
  size_t beyond_4_sigma = 0;         // |a - f| > 4 sqrt(σa² + σf²)
  size_t penumbra_made_hard = 0;     // full in the penumbra, adaptive exactly 0 or 1
  double worst_z = 0;                // max |a - f| / sqrt(σa² + σf²) where σ > 0
};

Agreement compare_with_full(const sb::reference::GBuffer& g, const Result& a, const Result& f) {
  Agreement out;
  for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
    if (!covered(g, i)) continue;
    ++out.covered;
    const double av = a.visibility.data[i], fv = f.visibility.data[i];
    const double sa = a.std_error.data[i], sf = f.std_error.data[i];
    const double sigma = std::sqrt(sa * sa + sf * sf);
    const double d = std::abs(av - fv);
    if (d > 4.0 * sigma) ++out.beyond_4_sigma;
    if (sigma > 0) out.worst_z = std::max(out.worst_z, d / sigma);
    if (fv > 0.0 && fv < 1.0) {
      ++out.penumbra;
      if (av == 0.0 || av == 1.0) ++out.penumbra_made_hard;
    }
  }
  return out;
}

void expect_agreement_with_full(const sb::core::Scene& scene, const std::string& label,
                                int pilot = 16) {
  const sb::reference::GBuffer g = sb::reference::trace_gbuffer(scene, kWidth, kHeight);
  const Result full = sb::reference::compute(scene, g.positions, g.normals, {256, 1});
  const Result a =
      sb::reference::compute(scene, g.positions, g.normals, adaptive(256, 0.02, pilot));
  ASSERT_EQ(a.method, sb::reference::kAdaptiveMethod);
  const Agreement m = compare_with_full(g, a, full);
  std::printf(
      "%s, pilot %d: %zu covered px, %zu in the full reference's penumbra; adaptive mean %.1f, max "
      "%d spp "
      "(full %.3f s, adaptive %.3f s); %zu beyond 4 sigma, worst %.2f sigma; %zu penumbra px "
      "made 0 or 1\n",
      label.c_str(), pilot, m.covered, m.penumbra, a.mean_spp, a.max_spp, full.seconds, a.seconds,
      m.beyond_4_sigma, m.worst_z, m.penumbra_made_hard);
  EXPECT_GT(m.penumbra, 200u) << label << ": too little penumbra to test anything";
  EXPECT_EQ(m.beyond_4_sigma, 0u) << label;
  EXPECT_EQ(m.penumbra_made_hard, 0u) << label;
  EXPECT_EQ(a.max_spp, 256 + pilot) << label << ": the penumbra never reached the full count";
  EXPECT_LT(a.mean_spp, 0.5 * 256) << label << ": adaptive sampling saved little";
  EXPECT_LE(a.penumbra_rms_std_error, 0.02) << label;
}

TEST(ReferenceAdaptive, AgreesWithTheFullCountOnTheSphereGrid) {
  expect_agreement_with_full(sb::test::scene_of_type("sphere_grid", {{"grid", 4}}), "sphere grid");
}

TEST(ReferenceAdaptive, AgreesWithTheFullCountOnAJeep) {
  expect_agreement_with_full(sb::test::scene_of_type("jeep"), "jeep");
}

TEST(ReferenceAdaptive, AgreesWithTheFullCountOnFoliage) {
  expect_agreement_with_full(sb::test::scene_of_type("foliage"), "foliage");
}

// Foliage's leaves are alpha-masked: the proofs take each leaf as its
// whole quad, which holds the mask's shape, so a pilot they prove lit sees
// the whole light through the masks too, and the masked leaves, never
// closed, prove no pilot occluded. Every proven pixel (its pilot's samples
// only, standard error 0) has the full count's value, on five seeds.
TEST(ReferenceAdaptive, ProvesPilotsAmongAlphaMaskedCastersOnlyWhereTheFullCountAgrees) {
  const sb::core::Scene scene = sb::test::scene_of_type("foliage");
  ASSERT_TRUE(std::any_of(scene.meshes.begin(), scene.meshes.end(), [](const sb::core::Mesh& m) {
    return m.casts_shadow && m.alpha_tested();
  }));
  const sb::reference::GBuffer g = sb::reference::trace_gbuffer(scene, kWidth, kHeight);
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Result full = sb::reference::compute(scene, g.positions, g.normals, {256, seed});
    Settings s = adaptive(256, 0.02, 4);
    s.seed = seed;
    const Result a = sb::reference::compute(scene, g.positions, g.normals, s);
    EXPECT_EQ(a.unproven_stops, 0);
    EXPECT_EQ(a.stop_bias_bound, 0.0);
    size_t proven = 0, wrong = 0;
    for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
      if (!covered(g, i) || a.samples.data[i] != 4.0f) continue;
      EXPECT_EQ(a.std_error.data[i], 0.0f) << "pixel " << i;
      ++proven;
      wrong += a.visibility.data[i] != full.visibility.data[i] ? 1 : 0;
    }
    EXPECT_GT(proven, 5000u);
    EXPECT_EQ(wrong, 0u);
  }
}

// A 4-sample pilot misses more: the window and the whole-light proof must
// still catch every penumbra pixel it missed.
TEST(ReferenceAdaptive, AgreesWithTheFullCountFromAFourSamplePilot) {
  expect_agreement_with_full(sb::test::scene_of_type("sphere_grid", {{"grid", 4}}), "sphere grid",
                             4);
  expect_agreement_with_full(sb::test::scene_of_type("jeep"), "jeep", 4);
  expect_agreement_with_full(sb::test::scene_of_type("foliage"), "foliage", 4);
}

// Against the exact reference, on the scenes it can do (foliage's leaves
// are alpha-masked: it has none). The criterion is the uniform reference's
// in test_exact_agreement.cpp: 4 of the stated errors, floored at one
// sample's weight at the pixel, on all but 0.1% of the covered pixels.
void expect_agreement_with_exact(const sb::core::Scene& scene, const std::string& label,
                                 int pilot = 16) {
  const sb::reference::GBuffer g = sb::reference::trace_gbuffer(scene, kWidth, kHeight);
  Settings exact_settings;
  exact_settings.exact = true;
  const Result exact = sb::reference::compute(scene, g.positions, g.normals, exact_settings);
  ASSERT_EQ(exact.method, sb::reference::kExactMethod) << exact.exact_fallback;
  const Result a =
      sb::reference::compute(scene, g.positions, g.normals, adaptive(256, 0.02, pilot));
  size_t covered_px = 0, outside = 0, penumbra = 0, made_hard = 0;
  for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
    if (!covered(g, i)) continue;
    ++covered_px;
    const double e = exact.visibility.data[i], av = a.visibility.data[i];
    const double floor = 1.0 / double(std::max(a.samples.data[i], 1.0f));
    outside += std::abs(e - av) > 4.0 * std::max(double(a.std_error.data[i]), floor);
    // A penumbra wider than one stratum of the pilot cannot hide from it.
    if (e > 0.05 && e < 0.95) {
      ++penumbra;
      made_hard += av == 0.0 || av == 1.0;
    }
  }
  std::printf(
      "%s vs exact, pilot %d: %zu covered px, %zu beyond 4 sigma, %zu of %zu soft px made hard\n",
      label.c_str(), pilot, covered_px, outside, made_hard, penumbra);
  EXPECT_GT(penumbra, 200u) << label;
  EXPECT_LE(double(outside), 0.001 * double(covered_px)) << label;
  EXPECT_EQ(made_hard, 0u) << label;
}

TEST(ReferenceAdaptive, AgreesWithTheExactReferenceOnTheSphereGrid) {
  expect_agreement_with_exact(sb::test::scene_of_type("sphere_grid", {{"grid", 4}}), "sphere grid");
}

TEST(ReferenceAdaptive, AgreesWithTheExactReferenceOnAJeep) {
  expect_agreement_with_exact(sb::test::scene_of_type("jeep"), "jeep");
}

TEST(ReferenceAdaptive, AgreesWithTheExactReferenceFromAFourSamplePilot) {
  expect_agreement_with_exact(sb::test::scene_of_type("sphere_grid", {{"grid", 4}}), "sphere grid",
                              4);
  expect_agreement_with_exact(sb::test::scene_of_type("jeep"), "jeep", 4);
}

// A pixel refined to the full count traces the uniform reference's very
// rays: with a target no estimate reaches, every refined pixel goes to the
// full count and equals the uniform reference bit for bit, error included.
TEST(ReferenceAdaptive, APixelRefinedToTheFullCountEqualsTheUniformReference) {
  const sb::core::Scene scene = sbtest::sphere_over_plane();
  const sb::reference::GBuffer g = sb::reference::trace_gbuffer(scene, 96, 72);
  const Result uniform = sb::reference::compute(scene, g.positions, g.normals, {64, 3});
  Settings s = adaptive(64, 1e-9, 4);
  s.seed = 3;
  const Result a = sb::reference::compute(scene, g.positions, g.normals, s);
  size_t full = 0, pilot_only = 0;
  for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
    if (!covered(g, i)) continue;
    if (a.samples.data[i] == 64.0f + 4.0f) {  // the full count and the pilot
      ++full;
      EXPECT_EQ(a.visibility.data[i], uniform.visibility.data[i]) << "pixel " << i;
      EXPECT_EQ(a.std_error.data[i], uniform.std_error.data[i]) << "pixel " << i;
    } else {
      EXPECT_EQ(a.samples.data[i], 4.0f) << "pixel " << i << ": stopped between levels";
      ++pilot_only;
    }
  }
  EXPECT_GT(full, 300u);
  EXPECT_GT(pilot_only, 1000u);
}

// The same on a linear light, whose strata nest along the segment.
TEST(ReferenceAdaptive, NestsAlongASegmentLight) {
  sb::core::Scene scene = sbtest::sphere_over_plane();
  scene.light.half_v = {0, 0, 0};
  const sb::reference::GBuffer g = sb::reference::trace_gbuffer(scene, 96, 72);
  const Result uniform = sb::reference::compute(scene, g.positions, g.normals, {256, 1});
  const Result a = sb::reference::compute(scene, g.positions, g.normals, adaptive(256, 1e-9));
  size_t full = 0;
  for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
    if (!covered(g, i) || a.samples.data[i] != 256.0f + 16.0f) continue;
    ++full;
    EXPECT_EQ(a.visibility.data[i], uniform.visibility.data[i]) << "pixel " << i;
  }
  EXPECT_GT(full, 100u);
  const Agreement m = compare_with_full(g, a, uniform);
  EXPECT_EQ(m.penumbra_made_hard, 0u);
}

// The estimate at a level below the full count is unbiased: averaged over
// seeds, the pilots alone (a target every pilot meets) converge on the
// exact visibility of a point in a wide penumbra.
TEST(ReferenceAdaptive, EstimatesBelowTheFullCountAreUnbiased) {
  const sb::core::Scene scene = sbtest::sphere_over_plane();
  const sb::reference::GBuffer g = sb::reference::trace_gbuffer(scene, 48, 36);
  Settings exact_settings;
  exact_settings.exact = true;
  const Result exact = sb::reference::compute(scene, g.positions, g.normals, exact_settings);
  std::vector<double> sum(g.positions.pixel_count(), 0.0);
  constexpr int kSeeds = 200;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    Settings s = adaptive(1024, 0.5);  // every mixed pilot meets it: pilots only
    s.seed = uint64_t(seed);
    const Result a = sb::reference::compute(scene, g.positions, g.normals, s);
    for (size_t i = 0; i < sum.size(); ++i) sum[i] += a.visibility.data[i];
  }
  size_t soft = 0;
  for (size_t i = 0; i < sum.size(); ++i) {
    const double e = exact.visibility.data[i];
    if (!covered(g, i) || !(e > 0.2 && e < 0.8)) continue;
    ++soft;
    // 16 stratified samples: σ ≤ 1/8 per seed, ≤ 0.0089 over 200 seeds.
    EXPECT_NEAR(sum[i] / kSeeds, e, 0.04) << "pixel " << i;
  }
  EXPECT_GT(soft, 20u);
}

// A speck a little above the ground over one pixel's point, hiding a
// fifth or so of the light from it and nothing from its neighbours: an
// isolated penumbra pixel in a lit neighbourhood, which a 5×5 window of
// agreeing pilots would let through whenever its own 4-sample pilot misses
// the speck (about 4 seeds in 10). The proof that an agreeing pilot sees
// the whole light fails there, so it is refined to the full count, on
// every seed.
TEST(ReferenceAdaptive, AnIsolatedPenumbraPixelAmongLitNeighboursIsStillRefined) {
  sb::core::Scene scene = sbtest::sphere_over_plane();
  scene.meshes.resize(1);  // the ground alone
  const sb::reference::GBuffer plain = sb::reference::trace_gbuffer(scene, 96, 72);
  const size_t pix = 40 * 96 + 60;
  ASSERT_TRUE(covered(plain, pix));
  // The pyramid to the light is about 0.02 across there; the speck's legs
  // are 0.008.
  scene.meshes.push_back(
      sbtest::speck_over(scene, sbtest::position_at(plain.positions, pix), 0.004f, 0.004f));
  const sb::reference::GBuffer g = sb::reference::trace_gbuffer(scene, 96, 72);
  int soft = 0;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    Settings full(256, seed);
    Settings s = adaptive(256, 0.02, 4);
    s.seed = seed;
    const Result f = sb::reference::compute(scene, g.positions, g.normals, full);
    const Result a = sb::reference::compute(scene, g.positions, g.normals, s);
    ASSERT_GT(f.visibility.data[pix], 0.5f);
    ASSERT_LT(f.visibility.data[pix], 0.97f);
    soft += 1;
    EXPECT_EQ(a.visibility.data[pix], f.visibility.data[pix]);
    EXPECT_EQ(compare_with_full(g, a, f).penumbra_made_hard, 0u);
  }
  EXPECT_EQ(soft, 10);
}

TEST(ReferenceAdaptive, ResultsDoNotDependOnTheThreadCount) {
  const sb::core::Scene scene = sbtest::sphere_over_plane();
  const sb::reference::GBuffer g = sb::reference::trace_gbuffer(scene, 96, 72);
  const Result many = sb::reference::compute(scene, g.positions, g.normals, adaptive(256, 0.02));
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const Result single = sb::reference::compute(scene, g.positions, g.normals, adaptive(256, 0.02));
  EXPECT_EQ(many.visibility.data, single.visibility.data);
  EXPECT_EQ(many.std_error.data, single.std_error.data);
  EXPECT_EQ(many.samples.data, single.samples.data);
}

TEST(ReferenceAdaptive, RefusesCountsThatDoNotNest) {
  const sb::core::Scene scene = sbtest::sphere_over_plane();
  const sb::reference::GBuffer g = sb::reference::trace_gbuffer(scene, 8, 6);
  for (const auto& [spp, pilot] : {std::pair{100, 16}, {32, 16}, {256, 8}, {4, 16}}) {
    SCOPED_TRACE(std::to_string(spp) + "/" + std::to_string(pilot));
    EXPECT_THROW(sb::reference::compute(scene, g.positions, g.normals, adaptive(spp, 0.01, pilot)),
                 std::invalid_argument);
  }
  EXPECT_EQ(sb::reference::detail::adaptive_layout_problem(1024, 16), "");
  EXPECT_EQ(sb::reference::detail::adaptive_layout_problem(64, 64), "");
  EXPECT_NE(sb::reference::detail::adaptive_layout_problem(100, 16).find("times a power of 4"),
            std::string::npos);
}

}  // namespace
