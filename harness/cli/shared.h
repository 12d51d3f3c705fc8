#pragma once
// What several commands share: the arguments they have in common (their
// options are declared once, in cli/options.h), and what they do with them:
// load the plugins and the config, name run folders, write CI outputs.
#include <string>
#include <utility>
#include <vector>

#include "config/experiment.h"
#include "plugin/registry.h"
#include "record/job_record.h"

namespace sb::cli {

// CONFIG, --plugins and --max-jobs: run, validate, plan.
struct ExperimentArgs {
  explicit ExperimentArgs(std::string command_path) : command(std::move(command_path)) {}
  std::string command;  // for messages: "run"
  std::string config;
  std::string plugins;
  double max_jobs = double(config::ExperimentLimits{}.max_jobs);
};

// --benchmark-out and --bencher-out of run and report.
struct CiOutputs {
  std::string benchmark_out, bencher_out;
};

// How run and compare-builds render and cache references.
struct ReferenceArgs {
  std::string backend = "osmesa";
  std::string cache_dir = "results/cache";
  bool no_cache = false;
  std::string embree_config;
};

// The plugins of `plugins` (or the installed folder when empty) and of
// $SHADOWBENCH_PLUGIN_PATH; exits with code 3 when none load.
plugin::Registry load_registry(const std::string& plugins);

// `config`, or InputError naming `command` when it is empty.
std::string one_config(const std::string& config, const std::string& command);

// CONFIG loaded and checked against the plugins and --max-jobs, with a
// warning on stderr for each parameter a technique declares but never reads
// and for each technique whose shadow-map size differs from the others'.
config::Experiment load_checked_experiment(const ExperimentArgs& a, const plugin::Registry& r);

// "<name>-<UTC yyyymmdd-hhmmss>": a run folder's default name.
std::string default_run_id(const std::string& name);

void write_ci_outputs(const CiOutputs& outputs, const std::vector<record::JobRecord>& records);

}  // namespace sb::cli
