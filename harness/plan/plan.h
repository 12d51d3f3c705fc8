#pragma once
// The plan stage: config → plan → run. Everything the runner would otherwise
// decide on its own is decided here, on the CPU, before any GL context
// exists: which scenes build, which (scene, technique) pairs are skipped and
// why, and which derived data each scene needs (the union of the needs of
// the techniques that will run on it). `shadowbench plan` and `validate`
// print it (`plan --json` writes it, plan/plan_json.h); `run` writes it to
// the run folder as plan.json and executes its jobs. The run uses the plan's
// build of a scene when the plan kept it (make_plan's keep_bytes), adding
// the Run needs' data; else it builds the scene again and the executor
// checks that it leads to the same decisions (outcome_mismatch).
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
  // What was derived: with Decide, the Run needs are left for the run, and
  // log's last `deferred_log` lines say so ("... (built when run)").
  Derive derived_for = Derive::Decide;
  size_t deferred_log = 0;
  // make_plan kept this build (the scene and its data, or its error) for the
  // run, which uses it instead of building the scene again; when false only
  // scene.inputs is left.
  bool kept = false;
};

// Builds the scene and decides its jobs. Never throws for bad scene input:
// it is recorded in `error` and `bad_input`.
ScenePlan plan_scene(const config::Experiment& e, const config::SceneVariant& sv, Derive derive);

// Makes a Derive::Decide plan of a scene what plan_scene(..., Derive::All)
// would have made, in place: derives the Run needs of the techniques that
// will run (their lines replace the "built when run" ones), without building
// the scene or deriving its Plan needs again. Does nothing for a scene that
// did not build or is derived already; a failure is recorded in `error`.
void derive_run_needs(const config::Experiment& e, ScenePlan& p);

// What keeping a built scene costs: the bytes of its meshes' vertex and
// index arrays and of its textures.
size_t scene_bytes(const core::Scene& scene);

// Drops a plan's scene data but the files it was built from (for the jobs'
// identity, run/job_identity.h); `kept` becomes false.
void drop_scene_data(ScenePlan& p);

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
  std::vector<ScenePlan> scenes;  // Derive::Decide plans; the data of those not kept dropped
  std::vector<PlannedJob> jobs;   // scene-major, then resolution, then technique
  int shard_count = 1;
  size_t count(PlannedJob::Status s) const;
};

// The whole experiment's plan, without GL, its jobs laid out in
// `shard_count` shards (plan/shards.h). Each scene is built once to decide
// its jobs; its build is kept (ScenePlan::kept) while the scenes kept, in
// plan order, hold at most `keep_bytes` (scene_bytes) together, so that a
// sweep of big scenes is not held at once. The only scene of an experiment is
// kept whatever its size when keep_bytes > 0: the run would build it again
// at once. keep_bytes 0 (plan, validate) keeps none.
Plan make_plan(const config::Experiment& e, int shard_count = 1, size_t keep_bytes = 0);

// make_plan's keep_bytes for a run (run/runner.h): 1 GiB, about 40 million
// triangles of meshes like bench/scene_once.py's (24 MB per million).
inline constexpr size_t kRunKeptSceneBytes = size_t(1) << 30;

// Human-readable: per scene, what it derives and infers; per job, run, skip
// or fail with the reason.
std::string describe_plan(const config::Experiment& e, const Plan& plan);

}  // namespace sb::plan
