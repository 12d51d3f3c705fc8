// Techniques against each other and against the ray-traced reference, on a
// small sphere grid at 160×120.
#include <gtest/gtest.h>

#include "e2e_util.h"
#include "metrics/metrics.h"

namespace sb::test {

using core::ImageF;

namespace {

using json = nlohmann::json;

json experiment(const json& scene, const json& techniques, int spp) {
  return {{"name", "t"},
          {"scenes", json::array({scene})},
          {"techniques", techniques},
          {"resolutions", json::array({json::array({160, 120})})},
          {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"spp", spp}}}};
}

TEST(Techniques, ShadowMapAndShadowVolumeAgreeForATinyLight) {
  const auto out = run_config(
      experiment(small_scene(1e-3),
                 json::array({json{{"name", "shadow_map"}, {"params", {{"size", 2048}}}},
                              json{{"name", "shadow_volume"},
                                   {"params", {{"mode", json::array({"zpass", "zfail"})}}}}}),
                 16),
      "tiny_light");
  ASSERT_EQ(out.summary.failed, 0);
  const ImageF sm = out.visibility("shadow_map/size=2048");
  for (const char* sv : {"shadow_volume/mode=zpass", "shadow_volume/mode=zfail"}) {
    const auto s = metrics::compare(out.visibility(sv), sm);
    // Both are hard: they may only differ on shadow-boundary pixels.
    EXPECT_LT(s.frac_over_01, 0.01) << sv;
    // And the shadow is really there: a twentieth of the pixels or more are dark.
    size_t dark = 0;
    for (float v : sm.data) dark += v < 0.5f;
    EXPECT_GT(dark, sm.pixel_count() / 20);
  }
}

TEST(Techniques, AccumulationMatchesTheRayTracedReference) {
  const auto out =
      run_config(experiment(small_scene(1.5),
                            json::array({json{{"name", "accumulation"},
                                              {"params", {{"samples", 256}, {"size", 1024}}}}}),
                            1024),
                 "accumulation");
  ASSERT_EQ(out.summary.failed, 0);
  const auto& m = out.record("accumulation/samples=256,size=1024")["metrics"]["visibility"]["all"];
  EXPECT_LT(m["rmse"].get<double>(), 0.02) << m.dump();
}

// A prime sample count used to give 1×N strata (thin columns, t left to
// chance); it must do about as well as the nearest square. Few samples make
// one seed's error a lottery, so the penumbra RMSE is averaged over eight.
TEST(Techniques, AccumulationWithAPrimeSampleCountIsAsGoodAsASquareOne) {
  const json seeds = json::array({1, 2, 3, 4, 5, 6, 7, 8});
  const auto out = run_config(
      experiment(
          small_scene(1.5),
          json::array({json{
              {"name", "accumulation"},
              {"params", {{"samples", json::array({13, 16})}, {"size", 512}, {"seed", seeds}}}}}),
          1024),
      "accumulation_prime");
  ASSERT_EQ(out.summary.failed, 0);
  const auto mean_penumbra_rmse = [&](int samples) {
    double sum = 0.0;
    for (const auto& seed : seeds) {
      const std::string variant = "accumulation/samples=" + std::to_string(samples) +
                                  ",seed=" + std::to_string(seed.get<int>()) + ",size=512";
      sum += out.record(variant)["metrics"]["visibility"]["penumbra"]["rmse"].get<double>();
    }
    return sum / double(seeds.size());
  };
  const double rmse13 = mean_penumbra_rmse(13), rmse16 = mean_penumbra_rmse(16);
  // Stratified error falls as N^-0.75: 13 samples should cost about
  // (16/13)^0.75 = 1.17 times the error of 16.
  EXPECT_LT(rmse13, 1.3 * rmse16) << rmse13 << " vs " << rmse16;
  RecordProperty("penumbra_rmse_13", std::to_string(rmse13));
  RecordProperty("penumbra_rmse_16", std::to_string(rmse16));
}

TEST(Techniques, PcfBeatsHardShadowMapForALargeLight) {
  const auto out = run_config(
      experiment(small_scene(3.0),
                 json::array({json{{"name", "shadow_map"}, {"params", {{"size", 1024}}}},
                              json{{"name", "pcf_box"}, {"params", {{"size", 1024}, {"k", 7}}}}}),
                 256),
      "pcf_large_light");
  ASSERT_EQ(out.summary.failed, 0);
  const double hard = out.record("shadow_map/size=1024")["metrics"]["visibility"]["all"]["rmse"];
  const double pcf = out.record("pcf_box/k=7,size=1024")["metrics"]["visibility"]["all"]["rmse"];
  EXPECT_LT(pcf, hard);
}

TEST(Techniques, NoneIsFullyLitAndTheReferenceIsNot) {
  const auto out = run_config(experiment(small_scene(1.0), json::array({"none"}), 16), "none");
  const ImageF v = out.visibility("none");
  for (float x : v.data) ASSERT_TRUE(x == 1.0f || x == 0.0f);  // 0 only in attached shadow
  const ImageF ref = out.reference_visibility();
  EXPECT_GT(metrics::compare(v, ref).rmse, 0.1);
}

}  // namespace
}  // namespace sb::test
