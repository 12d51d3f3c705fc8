// The plan's outcomes hold for the scene the executor builds (decide_job on
// a Derive::All plan of each scene), an altered outcome is caught
// (outcome_mismatch), and `plan --json` writes every job as make_plan
// planned it (a bad scene's: test_plan.cpp).
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "../config/cli_runner.h"
#include "config/experiment.h"
#include "plan/plan.h"
#include "plugin/registry.h"
#include "test_registry.h"

namespace sb::test {
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

}  // namespace
}  // namespace sb::test
