// The shadow-map family (PCF kernels, PCSS, VSM, ESM, EVSM, MSM, convolution
// maps) through the real driver: finiteness on every scene type, error
// against the ray-traced reference, and the failure modes each variant is
// known for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "e2e_util.h"
#include "metrics/metrics.h"

namespace sb::test {

using core::ImageF;

namespace {

using json = nlohmann::json;

json experiment(const json& scenes, const json& techniques, int width, int height, int spp) {
  return {{"name", "family"},
          {"scenes", scenes},
          {"techniques", techniques},
          {"resolutions", json::array({json::array({width, height})})},
          {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"spp", spp}}}};
}

json technique(const std::string& name, json params, const std::string& label = "") {
  json t = {{"name", name}, {"params", std::move(params)}};
  if (!label.empty()) t["label"] = label;
  return t;
}

double penumbra_rmse(const RunOutput& out, const std::string& variant) {
  return out.record(variant)["metrics"]["visibility"]["penumbra"]["rmse"].get<double>();
}

// Every variant, in each of its storage formats and modes, at small sizes.
json every_variant(int size) {
  return json::array({
      technique("shadow_map", {{"size", size}, {"depth_format", json::array({"32f", "24", "16"})}}),
      technique("pcf_box",
                {{"size", size}, {"k", 5}, {"filter", json::array({"nearest", "bilinear"})}}),
      technique("pcf_gauss", {{"size", size}, {"k", 7}, {"receiver_plane_bias", true}}),
      technique("pcf_jitter", {{"size", size}, {"rotate", json::array({true, false})}}),
      technique("pcss", {{"size", size}}),
      technique("vsm",
                {{"size", size}, {"prefilter", "gauss"}, {"format", json::array({"32f", "16f"})}}),
      technique("esm",
                {{"size", size}, {"prefilter", "box"}, {"exponent", json::array({80, 200})}}),
      technique("evsm", {{"size", size},
                         {"prefilter", "box"},
                         {"components", json::array({2, 4})},
                         {"format", json::array({"32f", "16f"})}}),
      technique("msm", {{"size", size}, {"prefilter", "box"}}),
      technique("csm_convolution", {{"size", size}, {"prefilter", "box"}, {"terms", 4}}),
  });
}

TEST(ShadowMapFamily, EveryVariantGivesFiniteVisibilityInUnitRangeOnEveryScene) {
  const json scenes = json::array({
      small_scene(1.0),
      json{{"type", "jeep"}, {"params", {{"count", 2}, {"tessellation", 8}}}},
      json{{"type", "foliage"}, {"params", {{"trees", 1}, {"depth", 2}}}},
      json{{"type", "plates"}, {"params", {{"layout", json::array({"edge", "stacked"})}}}},
  });
  const auto out = run_config(experiment(scenes, every_variant(256), 96, 72, 4), "family_finite");
  EXPECT_EQ(out.summary.failed, 0);
  EXPECT_EQ(out.summary.skipped, 0);
  EXPECT_EQ(out.records.size(), 5u * 19u);
  for (const auto& r : out.records) {
    SCOPED_TRACE(r["job_id"].get<std::string>());
    ASSERT_EQ(r["status"], "ok") << r.value("reason", "");
    EXPECT_EQ(r["visibility_check"]["nonfinite"], 0);
    EXPECT_EQ(r["visibility_check"]["below_0"], 0);
    EXPECT_EQ(r["visibility_check"]["above_1"], 0);
    // A shadow is there: no variant reads the whole frame as lit.
    EXPECT_GT(r["metrics"]["visibility"]["all"]["mae"].get<double>(), 0.0);
  }
}

// The stiff case that once broke MSM: dense alpha-tested foliage at full
// size, where a handful of the 480 000 pixels had filtered moments whose
// reconstruction divided by a difference that rounded to 0 (2 pixels Inf).
TEST(ShadowMapFamily, MomentReconstructionStaysFiniteOnDenseFoliage) {
  const auto out = run_config(
      experiment(json::array({json{{"type", "foliage"}}}),
                 json::array({technique("msm", {{"size", 2048}, {"prefilter", "box"}, {"k", 9}})}),
                 800, 600, 4),
      "family_msm_foliage");
  const auto& r = out.record("msm/size=2048,prefilter=box,k=9");
  EXPECT_EQ(r["status"], "ok") << r.value("reason", "");
  EXPECT_EQ(r["visibility_check"]["nonfinite"], 0);
}

// Double-sided leaves are never culled, so a lit leaf meets its own depth in
// a convolution map, where the truncated step reads ½. Annen et al.'s
// receiver offset of 1/(2M) puts lit leaves back at V ≈ 1.
TEST(ShadowMapFamily, ConvolutionMapsKeepLitLeavesLit) {
  const auto out = run_config(
      experiment(json::array({json{{"type", "foliage"}, {"params", {{"trees", 1}}}}}),
                 json::array({technique("csm_convolution", {{"size", 1024}}),
                              technique("csm_convolution", {{"size", 1024}, {"receiver_offset", 0}},
                                        "csm_no_offset")}),
                 160, 120, 16),
      "family_csm_leaves", gl::Backend::OSMesa, true, /*write_gbuffer=*/true);
  const ImageF positions = out.gbuffer_positions();
  const ImageF ref = out.reference_visibility();
  // Leaves and trunks: every surface above the ground whose reference is lit.
  const auto lit_leaf_shortfall = [&](const std::string& variant) {
    const ImageF v = out.visibility(variant);
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < ref.pixel_count(); ++i)
      if (positions.data[i * 4 + 3] != 0.0f && positions.data[i * 4 + 1] > 0.05f &&
          ref.data[i] == 1.0f) {
        sum += 1.0 - double(v.data[i]);
        ++n;
      }
    EXPECT_GT(n, 200u);
    return sum / double(std::max<size_t>(n, 1));
  };
  const double with_offset = lit_leaf_shortfall("csm_convolution/size=1024");
  const double without = lit_leaf_shortfall("csm_no_offset/receiver_offset=0,size=1024");
  std::printf("lit leaves: mean 1 - V %.4f with the offset, %.4f without\n", with_offset, without);
  EXPECT_LT(with_offset, 0.05);
  EXPECT_GT(without, 0.1) << "the defect the offset removes, as it was";
}

// Sphere grid, light side 2, 320×240, 1024² maps, 256-spp reference.
// Penumbra RMSE measured (llvmpipe, OSMesa; deterministic):
//   shadow_map 0.252 | pcf_box k7 0.216 | pcf_gauss k9 0.223 | pcf_jitter 0.212
//   pcss 0.106 | vsm 0.206 | esm 0.211 | evsm 0.204 | msm 0.201 | csm 0.231
// The light is wide for this close view: fixed kernels are too narrow, and
// PCSS, which sizes its kernel from the light, wins by a factor of two.
TEST(ShadowMapFamily, EveryFilteredVariantBeatsTheHardMapInThePenumbra) {
  const int size = 1024;
  const json filtered = {{"size", size}, {"prefilter", "box"}, {"k", 9}};
  const json techniques = json::array({
      technique("shadow_map", {{"size", size}}),
      technique("pcf_box", {{"size", size}, {"k", 7}}),
      technique("pcf_gauss", {{"size", size}, {"k", 9}}),
      technique("pcf_jitter", {{"size", size}}),
      technique("pcss", {{"size", size}}),
      technique("vsm", filtered),
      technique("esm", filtered),
      technique("evsm", filtered),
      technique("msm", filtered),
      technique("csm_convolution", filtered),
  });
  const auto out = run_config(
      experiment(json::array({small_scene(2.0)}), techniques, 320, 240, 256), "family_penumbra");
  ASSERT_EQ(out.summary.failed, 0);
  const double hard = penumbra_rmse(out, "shadow_map/size=1024");
  std::map<std::string, double> measured;
  for (const auto& r : out.records) {
    const std::string v = r["technique_variant"];
    measured[v] = penumbra_rmse(out, v);
    if (v == "shadow_map/size=1024") continue;
    EXPECT_LT(measured[v], hard) << v;
  }
  for (const auto& [v, e] : measured) std::printf("  %-50s penumbra RMSE %.4f\n", v.c_str(), e);
}

// ESM in log space stays finite at any exponent; storing exp(c·z) in fp32
// overflows once c·z > 88.7, and the harness fails the job.
TEST(ShadowMapFamily, LogSpaceEsmStaysFiniteWhereLinearStorageOverflows) {
  const json techniques = json::array({
      technique(
          "esm",
          {{"size", 512}, {"prefilter", "gauss"}, {"k", 5}, {"exponent", json::array({80, 200})}}),
      technique("esm",
                {{"size", 512},
                 {"prefilter", "gauss"},
                 {"k", 5},
                 {"exponent", json::array({80, 200})},
                 {"log_space", false}},
                "esm_linear"),
  });
  const auto out = run_config(experiment(json::array({small_scene(1.0)}), techniques, 160, 120, 16),
                              "family_esm");
  for (const char* v : {"esm/exponent=80,size=512,prefilter=gauss,k=5",
                        "esm/exponent=200,size=512,prefilter=gauss,k=5"}) {
    const auto& r = out.record(v);
    EXPECT_EQ(r["status"], "ok") << v << ": " << r.value("reason", "");
    EXPECT_EQ(r["visibility_check"]["nonfinite"], 0) << v;
  }
  // c = 80: exp(80) = 5.5e34 fits in fp32, so the linear map works too...
  const auto& ok80 =
      out.record("esm_linear/exponent=80,log_space=false,size=512,prefilter=gauss,k=5");
  EXPECT_EQ(ok80["status"], "ok") << ok80.value("reason", "");
  // ...and agrees with the log-space one pixel by pixel where nothing
  // overflows: both average exp(c·z) bilinearly, one in log space. (A
  // hardware-filtered z, a geometric mean of exp(c·z), differed here by 0.075.)
  const ImageF linear = out.visibility(
      "esm_linear/exponent=80,log_space=false,size=512,"
      "prefilter=gauss,k=5");
  const ImageF log_space = out.visibility("esm/exponent=80,size=512,prefilter=gauss,k=5");
  ASSERT_EQ(linear.data.size(), log_space.data.size());
  float worst = 0.0f;
  for (size_t i = 0; i < linear.data.size(); ++i)
    worst = std::max(worst, std::fabs(linear.data[i] - log_space.data[i]));
  EXPECT_LT(worst, 1e-4f);
  RecordProperty("esm_log_vs_linear_max_difference", std::to_string(worst));
  // c = 200: exp(200·z) is Inf for z > 0.44, Inf/Inf is NaN, and the job fails.
  const auto& bad =
      out.record("esm_linear/exponent=200,log_space=false,size=512,prefilter=gauss,k=5");
  EXPECT_EQ(bad["status"], "failed");
  EXPECT_GT(bad["visibility_check"]["nonfinite"].get<int>(), 0);
  EXPECT_NE(bad["reason"].get<std::string>().find("NaN/Inf"), std::string::npos);
}

}  // namespace
}  // namespace sb::test
