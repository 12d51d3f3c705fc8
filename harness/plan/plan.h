#pragma once
// The plan stage: config → plan → run. Everything the runner would otherwise
// decide on its own is decided here, on the CPU, before any GL context
// exists: which scenes build, which (scene, technique) pairs are skipped and
// why, and which derived data each scene needs (the union of the needs of
// the techniques that will run on it). `shadowbench plan` and `validate`
// print it (`plan --json` writes it, plan/plan_json.h); `run` writes it to
// the run folder as plan.json and executes its jobs, and the executor checks
// that the scene it builds leads to the same decisions (outcome_mismatch).
#include <cstddef>
#include <string>
#include <vector>

#include "config/experiment.h"
#include "core/scene.h"
#include "plan/need_resolution.h"

namespace sb::plan {

// One scene variant, planned.
struct ScenePlan {
  const config::SceneVariant* variant = nullptr;
  core::Scene scene;                                 // empty when the scene failed to build
  plugin::DerivedData derived;                       // for the techniques' needs, as far as asked
  std::vector<const plugin::NeedProvider*> uploads;  // GPU stages of the running techniques' needs
  std::vector<std::string> inferred_receivers;       // scenes/receiver_inference.h
  std::vector<std::string> skip_reason;              // per technique variant; "" = runs
  std::vector<std::vector<std::string>> needs;       // per technique variant (ResolvedNeeds)
  std::string error;             // why the scene could not be built: all its jobs fail
  bool bad_input = false;        // ... because its input (a glTF file, say) is bad
  std::string input_error;       // then the InputError's message (file and place)
  std::vector<std::string> log;  // one line per decision or derived datum
};

// Builds the scene and decides its jobs. Never throws for bad scene input:
// it is recorded in `error` and `bad_input`.
ScenePlan plan_scene(const config::Experiment& e, const config::SceneVariant& sv, Derive derive);

// What is decided for one job before it runs.
struct JobOutcome {
  enum class Status { Run, Skip, Fail } status = Status::Run;
  std::string reason;       // for Skip and Fail
  bool bad_input = false;   // Fail because the scene's input (a glTF file, say) is bad:
  std::string input_error;  // then the InputError's message (file and place)
  bool operator==(const JobOutcome&) const = default;
};
const char* to_string(JobOutcome::Status status);  // "run", "skip", "fail"

// The decision for technique variant `technique` on a planned scene: fail
// when its plugin did not load or the scene did not build, skip with the
// needs' reason, else run. The one rule both the plan and the executor apply.
JobOutcome decide_job(const config::Experiment& e, const ScenePlan& scene, size_t technique);

// "" when `decided` (the executor's decision, from the scene it built)
// equals the plan's outcome; else an internal-error reason naming both, for
// the job's failed record: a job never runs other than as planned.
std::string outcome_mismatch(const JobOutcome& planned, const JobOutcome& decided);

struct PlannedJob {
  using Status = JobOutcome::Status;
  std::string id;    // job_id(scene variant, resolution, technique variant)
  size_t index = 0;  // its place in Plan::jobs (a record's job_index)
  size_t scene = 0, resolution = 0, technique = 0;  // indices into the experiment
  double cost = 0;                                  // estimated (plan/shards.h)
  int shard = 1;                                    // 1-based, of Plan::shard_count
  JobOutcome outcome;
};

struct Plan {
  std::vector<ScenePlan> scenes;  // scene data dropped but its inputs (Derive::Decide plans)
  std::vector<PlannedJob> jobs;   // scene-major, then resolution, then technique
  int shard_count = 1;
  size_t count(PlannedJob::Status s) const;
};

// The whole experiment's plan, without GL and without keeping scene data,
// its jobs laid out in `shard_count` shards (plan/shards.h).
Plan make_plan(const config::Experiment& e, int shard_count = 1);

// Human-readable: per scene, what it derives and infers; per job, run, skip
// or fail with the reason.
std::string describe_plan(const config::Experiment& e, const Plan& plan);

}  // namespace sb::plan
