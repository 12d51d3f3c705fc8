// The plan's outcomes hold for the scene the executor builds (decide_job on
// a Derive::All plan of each scene), an altered outcome is caught
// (outcome_mismatch), and `plan --json` writes every job as make_plan
// planned it (a bad scene's: test_plan.cpp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "../config/cli_runner.h"
#include "config/experiment.h"
#include "core/error.h"
#include "plan/plan.h"
#include "plan/plan_json.h"
#include "plugin/registry.h"
#include "test_registry.h"

namespace sb::test {

using config::Experiment;
using config::load_experiment;
using core::InputError;
using plan::decide_job;
using plan::Derive;
using plan::JobOutcome;
using plan::make_plan;
using plan::outcome_mismatch;
using plan::Plan;
using plan::plan_record;
using plan::plan_scene;
using plan::plan_to_json;
using plan::PlannedJob;
using plan::read_plan_file;
using plan::to_string;
using record::plan_difference;
using record::PlanRecord;

namespace {

const std::string kScenes = std::string(SHADOWBENCH_SOURCE_DIR) + "/configs/scenes.json";

// What the executor decides for a job, from the scene built with every
// derived datum (run/job_executor.cpp).
JobOutcome executor_decision(const Experiment& e, const PlannedJob& j) {
  return decide_job(e, plan_scene(e, e.scenes[j.scene], Derive::All), j.technique);
}

TEST(PlanOutcomes, TheExecutorsDecisionsFromTheBuiltSceneMatchThePlan) {
  const Experiment e = load_experiment(kScenes, registry());
  const Plan plan = make_plan(e);
  size_t skipped = 0;
  for (const PlannedJob& j : plan.jobs) {
    EXPECT_EQ(outcome_mismatch(j.outcome, executor_decision(e, j)), "") << j.id;
    skipped += j.outcome.status == JobOutcome::Status::Skip ? 1 : 0;
  }
  EXPECT_EQ(skipped, 1u);  // foliage's shadow volume: both sides agree on a skip too
}

TEST(PlanOutcomes, AnAlteredOutcomeIsAMismatchNamingBothDecisions) {
  const Experiment e = load_experiment(kScenes, registry());
  Plan plan = make_plan(e);
  for (PlannedJob& j : plan.jobs) {
    const JobOutcome truth = executor_decision(e, j);
    if (j.outcome.status == JobOutcome::Status::Run) {
      j.outcome.status = JobOutcome::Status::Skip;
      j.outcome.reason = "altered for the test";
      const std::string why = outcome_mismatch(j.outcome, truth);
      EXPECT_NE(why.find("internal error"), std::string::npos) << why;
      EXPECT_NE(why.find("plan says skip (altered for the test)"), std::string::npos) << why;
      EXPECT_NE(why.find("says run"), std::string::npos) << why;
    } else {
      // The planned skip turned into a run.
      j.outcome = JobOutcome{};
      const std::string why = outcome_mismatch(j.outcome, truth);
      EXPECT_NE(why.find("plan says run"), std::string::npos) << why;
      EXPECT_NE(why.find("says skip (" + truth.reason + ")"), std::string::npos) << why;
    }
  }
  // The same status with another reason is a mismatch as well.
  JobOutcome a, b;
  a.status = b.status = JobOutcome::Status::Fail;
  a.reason = "one";
  b.reason = "two";
  EXPECT_NE(outcome_mismatch(a, b), "");
  b.reason = "one";
  EXPECT_EQ(outcome_mismatch(a, b), "");
}

TEST(PlanOutcomes, PlanJsonListsEveryJobWithItsOutcomeCostAndShard) {
  const Experiment e = load_experiment(kScenes, registry());
  const Plan plan = make_plan(e, 3);
  const auto r = run_cli("plan " + kScenes + " --shards 3 --json", false);
  EXPECT_EQ(r.exit_code, 0);
  const nlohmann::json j = nlohmann::json::parse(r.output, nullptr, false);
  ASSERT_TRUE(j.is_object()) << j;
  EXPECT_EQ(j["plan_version"], 1);
  EXPECT_EQ(j["shard_count"], 3);
  EXPECT_EQ(j["counts"]["run"], 23);
  EXPECT_EQ(j["counts"]["skip"], 1);
  ASSERT_EQ(j["jobs"].size(), 24u);  // 4 scenes × 6 techniques, one resolution
  ASSERT_EQ(j["scenes"].size(), 4u);
  std::set<std::string> ids;
  for (size_t i = 0; i < j["jobs"].size(); ++i) {
    const nlohmann::json& job = j["jobs"][i];
    const PlannedJob& p = plan.jobs[i];
    EXPECT_TRUE(ids.insert(job["id"].get<std::string>()).second);
    EXPECT_EQ(job["index"], i);
    EXPECT_EQ(job["id"], p.id);
    EXPECT_EQ(job["scene"], e.scenes[p.scene].name);
    EXPECT_EQ(job["resolution"], e.resolutions[p.resolution].label());
    EXPECT_EQ(job["technique"], e.techniques[p.technique].name);
    EXPECT_EQ(job["shard"], p.shard);
    EXPECT_DOUBLE_EQ(job["cost"].get<double>(), p.cost);
    const bool foliage_volume = job["scene"] == "foliage" &&
                                job["technique"].get<std::string>().starts_with("shadow_volume");
    EXPECT_EQ(job["outcome"], foliage_volume ? "skip" : "run") << job["id"];
    if (foliage_volume) {
      EXPECT_NE(job["reason"].get<std::string>().find("needs closed casters: mesh 'leaves'"),
                std::string::npos);
    }
  }
  EXPECT_NE(j["scenes"][0]["log"].dump().find("edge adjacency"), std::string::npos);
}

// plan.json read back is the plan that was written: every job's id, index,
// outcome, reason, cost and shard, and every scene's log.
TEST(PlanOutcomes, APlanFileReadsBackAsThePlanItWasWrittenFrom) {
  const Experiment e = load_experiment(kScenes, registry());
  const Plan plan = make_plan(e, 3);
  const std::string file = (std::filesystem::path(::testing::TempDir()) /
                            ("plan-" + std::to_string(::getpid()) + ".json"))
                               .string();
  std::ofstream(file) << plan_to_json(e, plan).dump(2) << "\n";
  const PlanRecord read = read_plan_file(file);
  EXPECT_EQ(read, plan_record(e, plan));
  ASSERT_EQ(read.jobs.size(), plan.jobs.size());
  for (size_t i = 0; i < plan.jobs.size(); ++i) {
    EXPECT_EQ(read.jobs[i].id, plan.jobs[i].id);
    EXPECT_EQ(read.jobs[i].outcome, to_string(plan.jobs[i].outcome.status));
    EXPECT_EQ(read.jobs[i].reason, plan.jobs[i].outcome.reason);
    EXPECT_EQ(read.jobs[i].shard, plan.jobs[i].shard);
    EXPECT_DOUBLE_EQ(read.jobs[i].cost, plan.jobs[i].cost);
  }
  EXPECT_EQ(read.scenes[0].log, plan.scenes[0].log);
  EXPECT_EQ(plan_difference(read, plan_record(e, plan)), "");
  std::filesystem::remove(file);
}

// "LINE:COL" (1-based, in bytes) of byte `at` of `text`.
std::string line_col(const std::string& text, size_t at) {
  const size_t line = 1 + static_cast<size_t>(std::count(text.begin(), text.begin() + at, '\n'));
  const size_t newline = text.rfind('\n', at == 0 ? 0 : at - 1);
  return std::to_string(line) + ":" +
         std::to_string(newline == std::string::npos ? at + 1 : at - newline);
}

// The byte just after the first `needle` in `text`.
size_t after(const std::string& text, const std::string& needle) {
  const size_t at = text.find(needle);
  return at == std::string::npos ? at : at + needle.size();
}

// A plan.json that is wrong is refused with its file, line, column and
// pointer: another version, an unknown outcome, counts the jobs contradict,
// a job out of its place or shard, a job without a member. Each altered
// value is one the text holds once, so its place is found in the text.
TEST(PlanOutcomes, AWrongPlanFileIsRefusedAtItsLineColumnAndPointer) {
  const Experiment e = load_experiment(kScenes, registry());
  const nlohmann::json good = plan_to_json(e, make_plan(e, 2));
  const std::string file = (std::filesystem::path(::testing::TempDir()) /
                            ("bad-plan-" + std::to_string(::getpid()) + ".json"))
                               .string();
  struct Case {
    std::function<void(nlohmann::json&)> alter;
    std::string pointer;
    std::function<size_t(const std::string&)> value_at;  // where the pointer's value starts
    std::string problem;
  };
  const std::vector<Case> cases = {
      {[](nlohmann::json& j) { j["plan_version"] = 2; }, "/plan_version",
       [](const std::string& t) { return after(t, "\"plan_version\": "); },
       "is 2; this build reads plan version 1 only"},
      {[](nlohmann::json& j) { j["jobs"][3]["outcome"] = "maybe"; }, "/jobs/3/outcome",
       [](const std::string& t) { return t.find("\"maybe\""); },
       "expected one of \"run\", \"skip\", \"fail\", found \"maybe\""},
      {[](nlohmann::json& j) { j["counts"]["run"] = 5; }, "/counts",
       [](const std::string& t) { return after(t, "\"counts\": "); },
       "say 5 run, 1 skip, 0 fail; the jobs are 23, 1 and 0"},
      {[](nlohmann::json& j) { j["jobs"][2]["index"] = 99; }, "/jobs/2/index",
       [](const std::string& t) { return after(t, "\"index\": 99") - 2; },
       "is 99 at place 2 of the jobs"},
      {[](nlohmann::json& j) { j["jobs"][1]["shard"] = 3; }, "/jobs/1/shard",
       [](const std::string& t) { return after(t, "\"shard\": 3") - 1; },
       "is 3, not within 1 to shard_count 2"},
      {[](nlohmann::json& j) { j["jobs"][0].erase("cost"); }, "/jobs/0",
       [](const std::string& t) { return t.find('{', after(t, "\"jobs\": [")); },
       "missing required key \"cost\" in this object"},
  };
  for (const Case& c : cases) {
    nlohmann::json j = good;
    c.alter(j);
    const std::string text = j.dump(2);
    std::ofstream(file) << text;
    const size_t at = c.value_at(text);
    ASSERT_NE(at, std::string::npos) << c.pointer;
    try {
      (void)read_plan_file(file);
      ADD_FAILURE() << c.pointer << ": accepted";
    } catch (const InputError& ex) {
      const std::string msg = ex.what();
      EXPECT_EQ(msg.rfind(file + ":" + line_col(text, at) + " (" + c.pointer + ")", 0), 0u) << msg;
      EXPECT_NE(msg.find(c.problem), std::string::npos) << msg;
    }
  }
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace sb::test
