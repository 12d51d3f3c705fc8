// configs/quick.json in three shards, merged, gives the records one run
// gives, timings aside; merge refuses what one comparison must not mix.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "scale_out_util.h"

namespace sb::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

const std::string kQuickConfig = std::string(SHADOWBENCH_SOURCE_DIR) + "/configs/quick.json";

TEST(ShardMerge, TheMergedShardsOfQuickEqualOneRunTimingsAside) {
  const auto dir = test_folder();
  const std::string cache = " --cache-dir " + (dir / "cache").string() + " --quiet";
  const CliRun whole =
      run_shadowbench("run " + kQuickConfig + " --out " + (dir / "whole").string() + cache);
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  std::string shard_dirs;
  for (int k = 1; k <= 3; ++k) {
    const fs::path out = dir / ("shard-" + std::to_string(k));
    std::string args = "run " + kQuickConfig;
    args += " --shard " + std::to_string(k) + "/3 --out " + out.string() + cache;
    const CliRun r = run_shadowbench(args);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    for (const auto& rec : jsonl_records(out)) EXPECT_EQ(rec["shard"], std::to_string(k) + "/3");
    shard_dirs += " " + out.string();
  }
  const CliRun merge = run_shadowbench("merge " + (dir / "merged").string() + shard_dirs);
  ASSERT_EQ(merge.exit_code, 0) << merge.output;
  EXPECT_NE(merge.output.find("merged 20 records"), std::string::npos) << merge.output;

  const auto one = jsonl_records(dir / "whole");
  const auto merged = jsonl_records(dir / "merged");
  ASSERT_EQ(one.size(), 20u);
  ASSERT_EQ(merged.size(), one.size());
  for (size_t i = 0; i < one.size(); ++i) {
    const json& a = one[i];
    const json& b = merged[i];  // the same order: the plan's
    EXPECT_EQ(a["job_id"], b["job_id"]) << i;
    EXPECT_EQ(a["spec_hash"], b["spec_hash"]);
    EXPECT_EQ(a["status"], b["status"]);
    EXPECT_EQ(a["reference"]["cache_key"], b["reference"]["cache_key"]) << a["job_id"];
    EXPECT_EQ(a["metrics"], b["metrics"]) << a["job_id"];
    EXPECT_EQ(a["classes"], b["classes"]) << a["job_id"];
    // Every image the merged record names is in the merged folder.
    for (const auto& [key, path] : b["images"].items())
      if (path.is_string()) {
        EXPECT_TRUE(fs::exists(dir / "merged" / path.get<std::string>())) << path;
      }
  }
  EXPECT_TRUE(fs::exists(dir / "merged" / "summary.md"));
  // The shards ran one plan: the merged folder keeps it, byte for byte.
  const auto text = [](const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  };
  EXPECT_FALSE(text(dir / "shard-1" / "plan.json").empty());
  EXPECT_EQ(text(dir / "merged" / "plan.json"), text(dir / "shard-1" / "plan.json"));
}

// Two shards of a three-job config, for the refusals.
fs::path two_shards(const fs::path& dir) {
  const json config = {{"name", "two"},
                       {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 2}}}}}},
                       {"techniques", {"none", "shadow_map", "pcf_box"}},
                       {"resolutions", {"64x48"}},
                       {"frames", {{"warmup", 0}, {"timed", 2}, {"control", nullptr}}},
                       {"reference", {{"spp", 4}}}};
  std::ofstream(dir / "two.json") << config.dump();
  for (int k = 1; k <= 2; ++k)
    EXPECT_EQ(run_shadowbench("run " + (dir / "two.json").string() + " --shard " +
                              std::to_string(k) + "/2 --out " +
                              (dir / ("s" + std::to_string(k))).string() + " --no-cache --quiet")
                  .exit_code,
              0);
  return dir;
}

TEST(ShardMerge, MergeRefusesTimingsFromAnotherHostUnlessAllowedAndThenTheReportSaysSo) {
  const auto dir = two_shards(test_folder());
  // The second shard as if another machine had timed it.
  {
    auto records = jsonl_records(dir / "s2");
    std::ofstream out(dir / "s2" / "results.jsonl", std::ios::trunc);
    for (auto& r : records) {
      r["host"]["fingerprint"] = "0123456789abcdef";
      r["host"]["name"] = "other-node";
      out << r.dump() << "\n";
    }
  }
  const std::string dirs = " " + (dir / "s1").string() + " " + (dir / "s2").string();
  const CliRun refused = run_shadowbench("merge " + (dir / "m1").string() + dirs);
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("come from 2 hosts or GL renderers"), std::string::npos)
      << refused.output;
  EXPECT_NE(refused.output.find("other-node"), std::string::npos);
  EXPECT_NE(refused.output.find("--allow-mixed-hosts"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "m1" / "results.jsonl"));

  const CliRun allowed =
      run_shadowbench("merge " + (dir / "m2").string() + dirs + " --allow-mixed-hosts");
  EXPECT_EQ(allowed.exit_code, 0) << allowed.output;
  std::ifstream summary(dir / "m2" / "summary.md");
  const std::string text{std::istreambuf_iterator<char>(summary), {}};
  EXPECT_NE(text.find("**Mixed hosts:** these jobs were timed on 2 hosts"), std::string::npos)
      << text;
  const CliRun report = run_shadowbench("report " + (dir / "m2").string());
  EXPECT_EQ(report.exit_code, 0) << report.output;
  std::ifstream html(dir / "m2" / "report" / "index.html");
  const std::string page{std::istreambuf_iterator<char>(html), {}};
  EXPECT_NE(page.find("Mixed hosts:"), std::string::npos);
}

TEST(ShardMerge, MergeRefusesAJobTwiceAndAnotherConfig) {
  const auto dir = two_shards(test_folder());
  const CliRun twice = run_shadowbench("merge " + (dir / "m").string() + " " +
                                       (dir / "s1").string() + " " + (dir / "s1").string());
  EXPECT_EQ(twice.exit_code, 2) << twice.output;
  EXPECT_NE(twice.output.find("two folders ran the same job"), std::string::npos) << twice.output;

  auto records = jsonl_records(dir / "s2");
  {
    std::ofstream out(dir / "s2" / "results.jsonl", std::ios::trunc);
    for (auto& r : records) {
      r["config_hash"] = "ffffffffffffffff";
      out << r.dump() << "\n";
    }
  }
  const CliRun other = run_shadowbench("merge " + (dir / "m").string() + " " +
                                       (dir / "s1").string() + " " + (dir / "s2").string());
  EXPECT_EQ(other.exit_code, 2) << other.output;
  EXPECT_NE(other.output.find("merge joins the shards of one config"), std::string::npos)
      << other.output;
}

std::string file_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The shards read each other's plan.json back: shards given the config by
// different paths still ran one plan, which the merged folder keeps; a
// merge without a shard names how many of the plan's jobs, of which shard,
// have no record; shards whose plans differ keep no plan, and say why.
TEST(ShardMerge, MergeReadsTheShardsPlansBackAndWarnsOfPlannedJobsNoFolderRecorded) {
  const auto dir = two_shards(test_folder());
  // Shard 2 again, from a copy of the config elsewhere.
  fs::create_directories(dir / "elsewhere");
  fs::copy_file(dir / "two.json", dir / "elsewhere" / "two.json");
  const CliRun s2 =
      run_shadowbench("run " + (dir / "elsewhere" / "two.json").string() + " --shard 2/2 --out " +
                      (dir / "s2b").string() + " --no-cache --quiet");
  ASSERT_EQ(s2.exit_code, 0) << s2.output;
  const json plan1 = json::parse(file_text(dir / "s1" / "plan.json"));
  const json plan2 = json::parse(file_text(dir / "s2b" / "plan.json"));
  ASSERT_NE(plan1["config"], plan2["config"]);

  const CliRun whole = run_shadowbench("merge " + (dir / "m").string() + " " +
                                       (dir / "s1").string() + " " + (dir / "s2b").string());
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  EXPECT_EQ(whole.output.find("warning"), std::string::npos) << whole.output;
  EXPECT_EQ(file_text(dir / "m" / "plan.json"), file_text(dir / "s1" / "plan.json"));

  // Without shard 2: its jobs, counted from the plan, are named missing.
  size_t in_shard_2 = 0;
  for (const json& j : plan1["jobs"]) in_shard_2 += j["shard"] == 2 ? 1 : 0;
  ASSERT_GT(in_shard_2, 0u);
  const CliRun part =
      run_shadowbench("merge " + (dir / "part").string() + " " + (dir / "s1").string());
  ASSERT_EQ(part.exit_code, 0) << part.output;
  const std::string n = std::to_string(in_shard_2);
  EXPECT_NE(part.output.find("merge: warning: " + n + " of the plan's " +
                             std::to_string(plan1["jobs"].size()) +
                             (in_shard_2 == 1 ? " jobs has" : " jobs have") +
                             " no record in these folders (shard 2 of 2: " + n + " of its " + n +
                             "): the merged results are incomplete"),
            std::string::npos)
      << part.output;

  // Plans that differ: shard 2's says another shard for its first job.
  json altered = plan2;
  for (json& j : altered["jobs"])
    if (j["shard"] == 2) {
      j["shard"] = 1;
      break;
    }
  std::ofstream(dir / "s2b" / "plan.json", std::ios::trunc) << altered.dump(2);
  const CliRun differ = run_shadowbench("merge " + (dir / "m2").string() + " " +
                                        (dir / "s1").string() + " " + (dir / "s2b").string());
  ASSERT_EQ(differ.exit_code, 0) << differ.output;
  EXPECT_NE(differ.output.find("the shards' plans differ"), std::string::npos) << differ.output;
  EXPECT_NE(differ.output.find("is in shard 2, there in shard 1"), std::string::npos)
      << differ.output;
  EXPECT_FALSE(fs::exists(dir / "m2" / "plan.json"));

  // A plan.json that is not one is refused, at its place.
  altered["plan_version"] = 7;
  std::ofstream(dir / "s2b" / "plan.json", std::ios::trunc) << altered.dump(2);
  const CliRun bad = run_shadowbench("merge " + (dir / "m3").string() + " " +
                                     (dir / "s1").string() + " " + (dir / "s2b").string());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find((dir / "s2b" / "plan.json").string() + ":"), std::string::npos)
      << bad.output;
  EXPECT_NE(bad.output.find("(/plan_version): is 7; this build reads plan version 1 only"),
            std::string::npos)
      << bad.output;
}

}  // namespace
}  // namespace sb::test
