#pragma once
// The subcommands, one file each (cmd_*.cpp). Each takes the parsed
// arguments and returns the exit code; bad input is thrown as InputError,
// which main() prints with exit code 2.
#include <string>
#include <vector>

#include "cli/command_line.h"
#include "config/experiment.h"
#include "plugin/registry.h"
#include "record/job_record.h"

namespace sb::cli {

int cmd_run(const Args& a);
int cmd_validate(const Args& a, bool show_plan);  // validate, plan
int cmd_list(const Args& a);
int cmd_report(const Args& a);
int cmd_compare(const Args& a);
int cmd_merge(const Args& a);
int cmd_compare_builds(const Args& a);
int cmd_scene_export(const Args& a);
int cmd_scene_info(const Args& a);
int cmd_help(const Args& a, CLI::App& app);
int cmd_completion(const Args& a, CLI::App& app);
int cmd_new_technique(const Args& a);
int cmd_history_add(const Args& a);
int cmd_history_report(const Args& a);

// The plugins of --plugins (or the installed folder) and of
// $SHADOWBENCH_PLUGIN_PATH; exits with code 3 when none load.
plugin::Registry load_registry(const Args& a);

// The CONFIG argument, or InputError when there is none.
std::string one_config(const Args& a);

// CONFIG loaded and checked against the plugins and --max-jobs, with a
// warning on stderr for each parameter a technique declares but never reads
// and for each technique whose shadow-map size differs from the others'.
config::Experiment load_checked_experiment(const Args& a, const plugin::Registry& r);

// "<name>-<UTC yyyymmdd-hhmmss>": a run folder's default name.
std::string default_run_id(const std::string& name);

// --benchmark-out and --bencher-out of run and report.
void write_ci_outputs(const Args& a, const std::vector<record::JobRecord>& records);

}  // namespace sb::cli
