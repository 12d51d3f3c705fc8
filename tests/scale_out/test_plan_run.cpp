// `run` executes the plan `plan --json` prints: it writes the same plan as
// plan.json, records every job of it with the planned outcome, runs exactly
// its shard's jobs under --shard, and resumes by its job ids (on
// configs/quick.json's jobs, small_quick()).
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <set>

#include "scale_out_util.h"

namespace sb::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// `plan ARGS --json`: its stdout alone (stderr says why a scene is bad), parsed.
json plan_json(const std::string& args, int expected_exit = 0) {
  FILE* pipe = ::popen(("'" SHADOWBENCH_EXE "' plan " + args + " --json 2>/dev/null").c_str(), "r");
  std::string out;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), int(buf.size()), pipe) != nullptr) out += buf.data();
  const int status = ::pclose(pipe);
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, expected_exit) << out;
  return json::parse(out, nullptr, false);
}

json read_json(const fs::path& file) {
  std::ifstream in(file);
  return json::parse(in, nullptr, false);
}

// Each planned job has one record, in plan order, whose status and reason
// are the plan's outcome (a run job may still fail while running: none of
// these configs' do).
void expect_records_follow_the_plan(const json& plan, const std::vector<json>& records) {
  ASSERT_EQ(records.size(), plan["jobs"].size());
  const std::map<std::string, std::string> status_of = {
      {"run", "ok"}, {"skip", "skipped"}, {"fail", "failed"}};
  for (size_t i = 0; i < records.size(); ++i) {
    const json& job = plan["jobs"][i];
    const json& rec = records[i];
    EXPECT_EQ(rec["job_id"], job["id"]) << i;
    EXPECT_EQ(rec["job_index"], job["index"]) << job["id"];
    EXPECT_EQ(rec["scene_variant"], job["scene"]) << job["id"];
    EXPECT_EQ(rec["technique_variant"], job["technique"]) << job["id"];
    EXPECT_EQ(rec["resolution"], job["resolution"]) << job["id"];
    EXPECT_EQ(rec["status"], status_of.at(job["outcome"].get<std::string>())) << job["id"];
    if (job["outcome"] != "run") {
      EXPECT_EQ(rec["reason"], job["reason"]) << job["id"];
    }
  }
}

TEST(PlanRun, QuickRecordsEveryPlannedJobAsPlannedWritesThePlanAndResumesByItsIds) {
  const fs::path dir = test_folder();
  const json plan = plan_json(small_quick());
  ASSERT_TRUE(plan.is_object());
  ASSERT_EQ(plan["jobs"].size(), 20u);  // 1 scene × 2 resolutions × 10 technique variants
  const std::string out = (dir / "run").string();
  const std::string args = "run " + small_quick() + " --out " + out + " --cache-dir " +
                           (dir / "cache").string() + " --quiet";
  const CliRun r = run_shadowbench(args);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_json(fs::path(out) / "plan.json"), plan);
  expect_records_follow_the_plan(plan, jsonl_records(out));
  // Every job resumed: its id is the plan's, its spec unchanged.
  const CliRun again = run_shadowbench(args);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("0 ok, 0 skipped, 0 failed, 20 resumed"), std::string::npos)
      << again.output;
  EXPECT_EQ(read_json(fs::path(out) / "plan.json"), plan);
}

TEST(PlanRun, SkipsAndBadInputFailuresAreRecordedAsPlanned) {
  const fs::path dir = test_folder();
  // Shadow volumes skip on foliage's alpha-tested leaves; the missing glTF
  // fails every job of its scene as bad input.
  const json config = {{"name", "outcomes"},
                       {"scenes",
                        {{{"type", "sphere_grid"}, {"params", {{"grid", 2}}}},
                         {{"type", "foliage"}},
                         {{"type", "gltf"}, {"params", {{"file", "missing.glb"}}}}}},
                       {"techniques", {"none", "shadow_volume"}},
                       {"resolutions", {"64x48"}},
                       {"frames", {{"warmup", 0}, {"timed", 2}, {"control", nullptr}}},
                       {"reference", {{"spp", 4}}}};
  const fs::path file = dir / "outcomes.json";
  std::ofstream(file) << config.dump();
  const json plan = plan_json(file.string(), 2);  // 2: a scene's input is bad
  ASSERT_TRUE(plan.is_object());
  EXPECT_EQ(plan["counts"], (json{{"run", 3}, {"skip", 1}, {"fail", 2}}));
  const std::string out = (dir / "run").string();
  const CliRun r =
      run_shadowbench("run " + file.string() + " --out " + out + " --no-cache --quiet");
  EXPECT_EQ(r.exit_code, 2) << r.output;  // bad input, the other scenes' jobs recorded
  EXPECT_EQ(read_json(fs::path(out) / "plan.json"), plan);
  expect_records_follow_the_plan(plan, jsonl_records(out));
}

TEST(PlanRun, AShardRunsExactlyThePlansJobsOfThatShard) {
  const fs::path dir = test_folder();
  const json plan = plan_json(small_quick() + " --shards 3");
  ASSERT_TRUE(plan.is_object());
  std::vector<std::string> planned;  // shard 2's, in plan order
  for (const json& job : plan["jobs"])
    if (job["shard"] == 2) planned.push_back(job["id"]);
  ASSERT_FALSE(planned.empty());
  const std::string out = (dir / "shard-2").string();
  const CliRun r = run_shadowbench("run " + small_quick() + " --shard 2/3 --out " + out +
                                   " --cache-dir " + (dir / "cache").string() + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_json(fs::path(out) / "plan.json"), plan);
  std::vector<std::string> ran;
  for (const json& rec : jsonl_records(out)) {
    ran.push_back(rec["job_id"]);
    EXPECT_EQ(rec["status"], "ok") << rec["job_id"];
  }
  EXPECT_EQ(ran, planned);
}

}  // namespace
}  // namespace sb::test
