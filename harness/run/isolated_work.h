#pragma once
// One (scene, resolution)'s jobs, rendered in child processes, so that what
// kills a process (a driver's segfault, an abort, an out-of-memory kill, a
// hung shader) fails one job, not the run.
//
// The child runs a JobExecutor and sends its events up a pipe as JSON lines
// (run/run_events.h). The parent keeps the child's stderr, the job it is in,
// and a deadline: limits.job_seconds from the job's start, or
// limits.setup_seconds from the child's start while no job has started. When
// the child dies or overruns:
//   - in a job: that job's record is failed with how the process ended and
//     the child's last stderr lines, and the jobs it had not reached run in
//     a fresh child;
//   - before any job finished (scene, G-buffer or reference): every job of
//     the group fails with that reason, since a fresh child would redo the
//     same set-up;
//   - between jobs: the rest run in a fresh child.
// Every retry ends at least one job, so the loop ends.
#include <string>

#include "config/experiment.h"
#include "run/job_executor.h"
#include "run/job_identity.h"
#include "run/run_events.h"
#include "run/runner.h"

namespace sb::run {

// The parent's side also hears the child's stderr, line by line.
class ParentEvents : public RunEvents {
 public:
  virtual void child_stderr(const std::string& line) = 0;
};

struct TimeLimits {
  double job_seconds = 0, setup_seconds = 0;
};

struct IsolatedOutcome {
  int crashed = 0;    // jobs failed because their process died
  int timed_out = 0;  // jobs failed because their process overran
};

// Runs `work`'s jobs of scene variant `scene`, one child after another, each
// job ending in one job_finished event. The children are forked: they read
// the parent's PlannedJobs that `work` points to, and each completes its own
// copy of `planned`, the plan's build of the scene (JobExecutor::run_scene);
// the parent's is left as it was. Throws std::runtime_error when a
// child cannot make its GL context (as the run would fail in-process).
IsolatedOutcome run_isolated(const config::Experiment& e, const RunOptions& o,
                             const EmbreeChoice& embree, size_t scene, const ResolutionWork& work,
                             plan::ScenePlan* planned, const TimeLimits& limits,
                             ParentEvents& events);

}  // namespace sb::run
