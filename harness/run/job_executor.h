#pragma once
// Runs jobs in this process, on a GL context of its own. For one scene
// variant: takes the plan's build of it, when the plan kept one, and derives
// its Run needs, or else builds it (with its derived data) and checks that it
// leads to the plan's decisions; uploads it once, and per resolution renders
// the G-buffer and the reference once, then prepares, times and measures
// each technique variant asked for, telling `events` as it goes. Which jobs
// to run (resumed ones are not) and in which process is the caller's choice
// (run/runner.cpp, run/isolated_work.h).
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "config/experiment.h"
#include "plan/plan.h"
#include "run/job_identity.h"
#include "run/run_events.h"
#include "run/runner.h"

namespace sb::run {

// One (scene, resolution)'s jobs, in plan order: the run's Plan's (made once
// in the parent; forked children share it).
struct ResolutionWork {
  size_t resolution = 0;
  std::vector<const plan::PlannedJob*> jobs;
  // The files the plan's build of the scene read (core::Scene::inputs), for
  // the records of jobs that end before a scene is built again.
  const std::vector<core::InputFile>* inputs = nullptr;
  // run --retime: the kept records of jobs to time again, by job id (the
  // results store's, which forked children share). Such a job is rendered
  // and timed as any other; its reference, metrics and images are the
  // record's, and nothing is measured against a reference.
  std::map<std::string, const record::JobRecord*> retime = {};
};

class JobExecutor {
 public:
  // Makes the GL context (which throws when the backend cannot start).
  JobExecutor(const config::Experiment& e, const RunOptions& o, EmbreeChoice embree,
              RunEvents& events);
  ~JobExecutor();
  JobExecutor(const JobExecutor&) = delete;
  JobExecutor& operator=(const JobExecutor&) = delete;

  // Every job of `work` ends in one job_finished event: ok, skipped (the
  // plan's reason) or failed (the error), so one failing job never stops the
  // others. A job whose planned outcome the built scene contradicts fails
  // with both (outcome_mismatch). `planned` is the plan's ScenePlan of the
  // scene: when it is kept (plan::ScenePlan::kept), its build is used and
  // completed in place (plan::derive_run_needs) instead of building the
  // scene again. Throws only for what breaks the process.
  void run_scene(size_t scene, const std::vector<ResolutionWork>& work,
                 plan::ScenePlan* planned = nullptr);

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sb::run
