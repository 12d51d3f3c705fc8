// The executor asserts that its decisions match the plan: a job whose
// planned outcome the scene it builds contradicts fails with both decisions
// named, and is neither run nor skipped the other way.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "config/experiment.h"
#include "e2e_util.h"
#include "plan/plan.h"
#include "plugin/registry.h"
#include "run/job_executor.h"
#include "run/job_identity.h"
#include "run/run_events.h"

namespace sb::test {

using config::Experiment;
using config::parse_experiment;
using plan::JobOutcome;
using plan::make_plan;
using plan::Plan;
using plan::PlannedJob;
using plugin::Registry;
using record::JobRecord;
using record::JobStatus;
using run::choose_embree;
using run::GlIdentity;
using run::JobExecutor;
using run::RunEvents;
using run::RunOptions;

namespace {

// The records the executor finishes, by job id.
class Recorded final : public RunEvents {
 public:
  void log(const std::string& /*line*/) override {}
  void backend(const GlIdentity& /*gl*/) override {}
  void scene_planned(const std::string& /*scene*/, const std::vector<std::string>& /*log*/,
                     const std::string& /*bad_input*/) override {}
  void phase(const std::string& /*scene*/, const std::string& /*resolution*/,
             const std::string& /*what*/) override {}
  void job_started(const JobRecord& /*base*/) override {}
  void job_finished(JobRecord record) override {
    const std::string id = record.job_id;
    records.emplace(id, std::move(record));
  }
  std::map<std::string, JobRecord> records;
};

TEST(PlanExecutor, AJobWhosePlannedOutcomeTheBuiltSceneContradictsFailsNamingBoth) {
  Registry registry;
  registry.load_plugins(SHADOWBENCH_PLUGIN_DIR);
  const nlohmann::json config = {{"name", "altered"},
                                 {"scenes", {small_scene(1.0)}},
                                 {"techniques", {"none", "shadow_map", "pcf_box"}},
                                 {"resolutions", {"32x24"}},
                                 {"frames", {{"warmup", 0}, {"timed", 1}, {"control", nullptr}}},
                                 {"reference", {{"spp", 4}}}};
  const Experiment e = parse_experiment(config, "altered.json", registry);
  Plan plan = make_plan(e);
  ASSERT_EQ(plan.jobs.size(), 3u);
  for (const PlannedJob& j : plan.jobs) ASSERT_EQ(j.outcome.status, JobOutcome::Status::Run);
  // shadow_map planned as a skip, pcf_box as a failure: the scene says run.
  plan.jobs[1].outcome.status = JobOutcome::Status::Skip;
  plan.jobs[1].outcome.reason = "altered to skip";
  plan.jobs[2].outcome.status = JobOutcome::Status::Fail;
  plan.jobs[2].outcome.reason = "altered to fail";

  RunOptions o;
  o.run_dir = fresh_test_folder("shadowbench_e2e_plan_executor_");
  o.cache_dir = "";
  o.write_images = false;
  o.quiet = true;
  Recorded events;
  JobExecutor executor(e, o, choose_embree(e, o), events);
  executor.run_scene(0, {{0, {&plan.jobs[0], &plan.jobs[1], &plan.jobs[2]}}});

  ASSERT_EQ(events.records.size(), 3u);
  const JobRecord& none = events.records.at(plan.jobs[0].id);
  EXPECT_EQ(none.status, JobStatus::Ok) << none.reason.value_or("");
  const JobRecord& skip = events.records.at(plan.jobs[1].id);
  EXPECT_EQ(skip.status, JobStatus::Failed);
  EXPECT_EQ(skip.reason.value_or(""),
            "internal error: the plan says skip (altered to skip), but the scene built to run it "
            "says run; the job was not run either way");
  EXPECT_FALSE(skip.duration_s.has_value());  // never rendered
  const JobRecord& fail = events.records.at(plan.jobs[2].id);
  EXPECT_EQ(fail.status, JobStatus::Failed);
  EXPECT_NE(fail.reason.value_or("").find("the plan says fail (altered to fail)"),
            std::string::npos)
      << fail.reason.value_or("");
  EXPECT_FALSE(fail.duration_s.has_value());
}

}  // namespace
}  // namespace sb::test
