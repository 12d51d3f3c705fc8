// The driver's bookkeeping: records, skips with reasons, resumption, outputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <numeric>

#include "e2e_util.h"
#include "scenes/need_providers.h"

namespace sb::test {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

json config_with(const json& scene, const json& techniques) {
  return {{"name", "runner"},
          {"scenes", json::array({scene})},
          {"techniques", techniques},
          {"resolutions", json::array({json::array({64, 48}), json::array({48, 32})})},
          {"frames", {{"warmup", 1}, {"timed", 3}}},
          {"reference", {{"spp", 16}}}};
}

TEST(Runner, WritesEveryOutputWithTimingAndMetrics) {
  const auto out =
      run_config(config_with(small_scene(1.0), json::array({"none", "shadow_map"})), "outputs");
  ASSERT_EQ(out.summary.ok, 4);
  for (const char* f : {"results.jsonl", "results.csv", "summary.md"})
    EXPECT_TRUE(fs::exists(fs::path(out.dir) / f)) << f;
  const auto& r = out.record("shadow_map");
  EXPECT_EQ(r["schema_version"], 1);
  EXPECT_EQ(r["timing_source"], "cpu_glfinish");
  EXPECT_EQ(r["timing"]["timed_frames"], 3);
  EXPECT_EQ(r["timing"]["frame"]["count"], 3);
  // The raw samples are kept, in frame order, and agree with the statistics.
  const auto frames = r["timing"]["frame"]["samples_ms"].get<std::vector<double>>();
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_DOUBLE_EQ(*std::min_element(frames.begin(), frames.end()),
                   r["timing"]["frame"]["min_ms"].get<double>());
  // Coarse pass timing by default: one bracket per technique, no passes.
  EXPECT_EQ(r["timing"]["pass_timing"], "coarse");
  EXPECT_FALSE(r["timing"].contains("passes"));
  EXPECT_EQ(r["timing"]["technique"]["samples_ms"].size(), 3u);
  EXPECT_TRUE(r["timing"]["shared"].contains("gbuffer"));
  EXPECT_GE(r["timing"]["frame"]["median_ms"].get<double>(),
            r["timing"]["technique"]["median_ms"].get<double>());
  EXPECT_EQ(r["reference"]["spp"], 16);
  // Where the job's wall time went: the phases cover it, and the overhead is
  // what is neither frames nor stability.
  const double duration = r["duration_s"].get<double>();
  double phases = 0.0;
  for (const char* k : {"prepare", "frames", "measure", "images", "stability"}) {
    ASSERT_TRUE(r["phases_s"].contains(k)) << k;
    EXPECT_GE(r["phases_s"][k].get<double>(), 0.0) << k;
    phases += r["phases_s"][k].get<double>();
  }
  EXPECT_LE(phases, duration);
  EXPECT_GT(phases, 0.9 * duration) << "the phases leave much of the job unaccounted for";
  // 1 compile + warm-up + 3 timed frames, each next to a control frame: at
  // least the timed frames' own time.
  const double timed_s = std::accumulate(frames.begin(), frames.end(), 0.0) / 1000.0;
  EXPECT_GE(r["phases_s"]["frames"].get<double>(), timed_s);
  EXPECT_NEAR(
      r["overhead_s"].get<double>(),
      duration - r["phases_s"]["frames"].get<double>() - r["phases_s"]["stability"].get<double>(),
      1e-9);
  for (const char* k : {"rmse", "mae", "max_error", "psnr", "ssim", "frac_over_0.01",
                        "frac_over_0.05", "frac_over_0.1"}) {
    EXPECT_TRUE(r["metrics"]["visibility"]["all"].contains(k)) << k;
    EXPECT_TRUE(r["metrics"]["shaded"]["penumbra"].contains(k)) << k;
  }
  for (const char* k :
       {"visibility", "shaded", "error_heatmap", "reference_visibility", "reference_std_error"})
    EXPECT_TRUE(fs::exists(fs::path(out.dir) / r["images"][k].get<std::string>())) << k;
}

TEST(Runner, SkipsWithAReasonAndBuildsNoAdjacencyForShadowMapsOnly) {
  const auto before = derived_data_counters();
  run_config(config_with(small_scene(1.0), json::array({"none"})), "nothing_derived");
  EXPECT_EQ(derived_data_counters().adjacency_builds, before.adjacency_builds);
  EXPECT_EQ(derived_data_counters().closedness_checks, before.closedness_checks);
  // Depth maps ask which casters are closed (they cull only those), not
  // for adjacency.
  run_config(config_with(small_scene(1.0), json::array({"shadow_map", "pcf_box"})), "no_adjacency");
  EXPECT_EQ(derived_data_counters().adjacency_builds, before.adjacency_builds);
  EXPECT_GT(derived_data_counters().closedness_checks, before.closedness_checks);

  const auto out =
      run_config(config_with(small_scene(1.0), json::array({"shadow_volume"})), "adjacency");
  EXPECT_GT(derived_data_counters().adjacency_builds, before.adjacency_builds);
  EXPECT_EQ(out.record("shadow_volume")["scene"]["derived"]["adjacency_built"], true);
}

TEST(Runner, ResumesFinishedJobsAndRerunsTheRest) {
  const json config = config_with(small_scene(1.0), json::array({"none", "shadow_map"}));
  const auto first = run_config(config, "resume");
  ASSERT_EQ(first.summary.ok, 4);
  fs::remove(fs::path(first.dir) / "records" /
             (first.record("shadow_map")["job_id"].get<std::string>() + ".json"));
  const auto second = run_config(config, "resume", gl::Backend::OSMesa, /*fresh=*/false);
  EXPECT_EQ(second.summary.resumed, 3);
  EXPECT_EQ(second.summary.ok, 1);
  EXPECT_EQ(second.records.size(), 4u);
}

}  // namespace
}  // namespace sb::test
