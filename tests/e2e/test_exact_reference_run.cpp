// The exact reference in a run: ok records on the sphere grid and the
// jeeps, a Monte Carlo fallback with its reason on foliage (alpha-masked
// leaves), no noise warning against it; and a second, Monte Carlo reference
// whose error exceeds the exact one's by the Monte Carlo reference's own
// variance, as its standard-error image predicts.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "e2e_util.h"

namespace sb {
namespace {

using json = nlohmann::json;

TEST(ExactReferenceRun, OkOnSphereGridAndJeepsAndAReasonedFallbackOnFoliage) {
  const json config = {
      {"scenes",
       {test::small_scene(1.0),
        {{"type", "jeep"}, {"params", {{"tessellation", 8}}}},
        {{"type", "foliage"}, {"params", {{"trees", 1}, {"depth", 1}, {"leaves_per_branch", 4}}}}}},
      {"techniques", {"none", {{"name", "pcf_box"}, {"params", {{"k", 3}, {"size", 256}}}}}},
      {"resolutions", {{64, 48}}},
      {"frames", {{"warmup", 0}, {"timed", 1}}},
      {"reference", {{"method", "exact"}, {"spp", 16}}}};
  const test::RunOutput out = test::run_config(config, "exact_reference_run");
  ASSERT_EQ(out.records.size(), 6u);
  for (const json& r : out.records) {
    SCOPED_TRACE(r["job_id"].get<std::string>());
    EXPECT_EQ(r["status"], "ok") << r.value("reason", "");
    const json& ref = r["reference"];
    const bool foliage = r["scene"]["type"] == "foliage";
    if (foliage) {
      EXPECT_EQ(ref["method"], "embree_stratified_packet16");
      EXPECT_EQ(ref["spp"], 16);
      ASSERT_TRUE(ref.contains("exact_fallback"));
      EXPECT_NE(ref["exact_fallback"].get<std::string>().find("alpha"), std::string::npos)
          << ref["exact_fallback"];
    } else {
      EXPECT_EQ(ref["method"], "exact_clipper");
      EXPECT_EQ(ref["spp"], 0);
      EXPECT_FALSE(ref.contains("exact_fallback"));
      EXPECT_EQ(ref["penumbra_rms_std_error"], 0.0);
      EXPECT_GT(ref["penumbra_pixels"], 0);
      // No noise, so no warning that the noise is near the error.
      for (const auto& w : r.value("warnings", json::array()))
        EXPECT_EQ(w.get<std::string>().find("reference noise"), std::string::npos) << w;
    }
    EXPECT_FALSE(r.contains("second_reference"));
  }
}

TEST(ExactReferenceRun, TheSecondMonteCarloReferenceAddsItsOwnVariance) {
  const json config = {
      {"scenes", {test::small_scene(1.5)}},
      {"techniques", {"none", "shadow_map"}},
      {"resolutions", {{160, 120}}},
      {"frames", {{"warmup", 0}, {"timed", 1}}},
      {"reference", {{"method", "exact"}, {"second_method", "monte_carlo"}, {"spp", 16}}}};
  const test::RunOutput out = test::run_config(config, "exact_second_reference");
  ASSERT_EQ(out.records.size(), 2u);
  for (const json& r : out.records) {
    SCOPED_TRACE(r["technique_variant"].get<std::string>());
    ASSERT_EQ(r["status"], "ok") << r.value("reason", "");
    ASSERT_TRUE(r.contains("second_reference"));
    const json& second = r["second_reference"];
    EXPECT_EQ(r["reference"]["method"], "exact_clipper");
    EXPECT_EQ(second["reference"]["method"], "embree_stratified_packet16");
    EXPECT_EQ(second["reference"]["spp"], 16);
    // Same pixels: the regions are the first reference's.
    EXPECT_EQ(second["visibility"]["all"]["pixel_count"],
              r["metrics"]["visibility"]["all"]["pixel_count"]);
    EXPECT_EQ(second["visibility"]["penumbra"]["pixel_count"],
              r["metrics"]["visibility"]["penumbra"]["pixel_count"]);
  }
  // `none` sees V = 1: its error is 1 - V_ref, and against the unbiased
  // Monte Carlo estimate E[(1 - V_mc)²] = (1 - V)² + σ². So the MSE grows by
  // the mean variance over the measured pixels, which the Monte Carlo
  // reference's own standard errors estimate (conservatively: strata are
  // paired to estimate it, which overstates a stratified estimate's variance).
  const json& none = out.record("none");
  const json& mc = none["second_reference"]["reference"];
  const double mse_exact = std::pow(none["metrics"]["visibility"]["all"]["rmse"].get<double>(), 2);
  const double mse_mc =
      std::pow(none["second_reference"]["visibility"]["all"]["rmse"].get<double>(), 2);
  const double pixels = none["metrics"]["visibility"]["all"]["pixel_count"].get<double>();
  const double predicted = std::pow(mc["penumbra_rms_std_error"].get<double>(), 2) *
                           mc["penumbra_pixels"].get<double>() / pixels;
  ASSERT_GT(predicted, 0.0);
  EXPECT_GT(mse_mc - mse_exact, 0.3 * predicted) << mse_mc << " vs " << mse_exact;
  EXPECT_LT(mse_mc - mse_exact, 1.2 * predicted) << mse_mc << " vs " << mse_exact;
}

}  // namespace
}  // namespace sb
