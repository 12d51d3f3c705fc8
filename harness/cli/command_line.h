#pragma once
// The command line, on CLI11: every subcommand with its own options, their
// defaults and one example in its --help; --version; and errors in the
// harness's words with exit code 2, naming the option (docs/cli.md is
// generated from this parser, and a test keeps the two equal).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/experiment.h"
#include "results/compare.h"

namespace CLI {
class App;
}

namespace sb::cli {

struct Args {
  std::string command;                // "run", ..., "scene export", "scene info"
  std::string config;                 // run, validate, plan, compare-builds
  std::string run_dir;                // report, history add
  std::string base_dir, new_dir;      // compare
  std::vector<std::string> names;     // list: techniques or scene types; help: a command
  std::string scene_spec, scene_out;  // scene export / info
  std::string shell;                  // completion
  std::string out, backend = "osmesa", cache_dir = "results/cache", plugins;
  bool no_cache = false, no_images = false, gbuffer = false, quiet = false;
  bool no_viewer_data = false;             // report: the image viewer without its data files
  bool markdown = false;                   // list, help
  bool record_schema = false;              // list
  bool plan_schema = false;                // list
  bool names_only = false;                 // list
  std::string benchmark_out, bencher_out;  // run, report: CI outputs
  bool latex = false;                      // report: paper tables
  std::vector<std::string> latex_columns;  // report: their columns
  std::string chart_style = "default";     // report: default or paper
  std::string embree_config;               // run: the reference's Embree ISA
  std::string pass_timing = "coarse";      // run
  double max_jobs = double(config::ExperimentLimits{}.max_jobs);  // run, validate, plan
  results::CompareOptions compare;                                // compare, compare-builds
  std::string builds_normalize = "control";                       // compare-builds' own default
  std::string base_binary, new_binary;                            // compare-builds
  std::string take_turns;               // run: IN_FD,OUT_FD (compare-builds, hidden)
  int turn_block = 5;                   // run, compare-builds: frames per turn
  std::string isolation = "group";      // run: job, group or none
  std::string shard;                    // run: K/N
  int shards = 1;                       // plan: N
  bool plan_json = false;               // plan: the plan as JSON (plan/plan_json.h)
  std::vector<std::string> merge_dirs;  // merge: the run folders
  bool allow_mixed_hosts = false;       // merge
  std::optional<double> job_timeout;    // run: seconds, over limits.job_seconds
  std::string new_name;                 // new-technique: NAME
  std::string family = "plugin_api";    // new-technique: the template
  std::string dir;                      // new-technique: the folder (default: NAME)

  // history add, report: the run's commit, the history file, the time plotted.
  std::string commit;
  std::string history_db = "results/history.sqlite";
  std::string history_time = "ratio";
};

// The App is deleted in command_line.cpp, so that holding one needs no
// <CLI/CLI.hpp>, whose App emits its inline virtual functions wherever it
// is destroyed: main.cpp took 13.1 CPU s at -O3 with it, 5.3 s without
// (Release, 2-core VM under load, 2026-12-06).
struct AppDeleter {
  void operator()(CLI::App* app) const;
};
using AppPtr = std::unique_ptr<CLI::App, AppDeleter>;

// The parser, writing into `args`. Kept alive for as long as `args` is read.
AppPtr make_command_line(Args& args);

// Parses argv into args. Returns -1 to go on with args.command, or the exit
// code to end with: 0 after --help or --version (printed to stdout), 2 after
// a usage error (printed to stderr as "shadowbench: error: ...").
int parse_command_line(CLI::App& app, int argc, const char* const* argv, Args& args);

// Every subcommand, depth first, as "run", "scene export", ...; for the
// reference, completion and tests.
std::vector<CLI::App*> all_commands(CLI::App& app);
std::string command_path(const CLI::App& command);

}  // namespace sb::cli
