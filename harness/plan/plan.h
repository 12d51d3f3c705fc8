#pragma once
// The plan stage: config → plan → run. Everything the runner would otherwise
// decide on its own is decided here, on the CPU, before any GL context
// exists: which scenes build, which (scene, technique) pairs are skipped and
// why, and which derived data each scene needs (the union of the needs of
// the techniques that will run on it). `shadowbench plan` and `validate`
// print it; the runner executes it.
#include <cstddef>
#include <string>
#include <vector>

#include "config/experiment.h"
#include "core/scene.h"
#include "plan/need_resolution.h"

namespace sb {

// One scene variant, planned.
struct ScenePlan {
  const SceneVariant* variant = nullptr;
  Scene scene;                                  // empty when the scene failed to build
  DerivedData derived;                          // for the techniques' needs, as far as asked
  std::vector<const NeedProvider*> uploads;     // GPU stages of the running techniques' needs
  std::vector<std::string> inferred_receivers;  // scenes/receiver_inference.h
  std::vector<std::string> skip_reason;         // per technique variant; "" = runs
  std::string error;             // why the scene could not be built: all its jobs fail
  bool bad_input = false;        // ... because its input (a glTF file, say) is bad
  std::string input_error;       // then the InputError's message (file and place)
  std::vector<std::string> log;  // one line per decision or derived datum
};

// Builds the scene and decides its jobs. Never throws for bad scene input:
// it is recorded in `error` and `bad_input`.
ScenePlan plan_scene(const Experiment& e, const SceneVariant& sv, Derive derive);

struct PlannedJob {
  std::string id;  // job_id(scene variant, resolution, technique variant)
  size_t scene = 0, resolution = 0, technique = 0;  // indices into the experiment
  enum class Status { Run, Skip, Fail } status = Status::Run;
  std::string reason;  // for Skip and Fail
};

struct Plan {
  std::vector<ScenePlan> scenes;  // scene data dropped (Derive::Decide plans)
  std::vector<PlannedJob> jobs;   // scene-major, then resolution, then technique
  size_t count(PlannedJob::Status s) const;
};

// The whole experiment's plan, without GL and without keeping scene data.
Plan make_plan(const Experiment& e);

// Human-readable: per scene, what it derives and infers; per job, run, skip
// or fail with the reason.
std::string describe_plan(const Experiment& e, const Plan& plan);

}  // namespace sb
