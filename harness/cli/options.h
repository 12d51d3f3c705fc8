#pragma once
// What the command files (cmd_*.cpp) declare their options with: value
// checks in the harness's words, and the options several commands take,
// each declared once here and bound to the arguments struct of the command
// that takes it (cli/shared.h).
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "cli/shared.h"

namespace sb::cli {

// Checks in the harness's words ("expected ..., found '...'"); CLI11
// prefixes the option's name. Their descriptions are empty: the help shows
// the option's type name alone.
CLI::Validator number_check();
// A number in [lo, hi]; else `what`, found '...'.
CLI::Validator bounded_check(double lo, double hi, const std::string& what);
// A whole number in [lo, hi]; else `what`, found '...'.
CLI::Validator whole_check(double lo, double hi, const std::string& what);
// A check by `check`, which throws std::invalid_argument with the message.
CLI::Validator parser_check(std::function<void(const std::string&)> check);

// An option whose value is one of `choices`, shown as "{a,b}" (which the
// completion reads too).
CLI::Option* add_choice(CLI::App* sub, const std::string& name, std::string& value,
                        const std::vector<std::string>& choices, const std::string& doc);

// A positional argument: its name is its placeholder, so no type name.
template <class T>
CLI::Option* add_argument(CLI::App* sub, const std::string& name, T& value,
                          const std::string& doc) {
  return sub->add_option(name, value, doc)->type_name("");
}

// --plugins DIR: run, validate, plan, list, new-technique, check-technique.
void add_plugins(CLI::App* sub, std::string& plugins);
// --max-jobs N: run, validate, plan.
void add_max_jobs(CLI::App* sub, double& max_jobs);
// --benchmark-out and --bencher-out: run, report.
void add_ci_outputs(CLI::App* sub, CiOutputs& outputs);
// --backend, --cache-dir, --no-cache, --embree-config: run, compare-builds.
void add_reference_options(CLI::App* sub, ReferenceArgs& reference);
// --turn-block N: run, compare-builds.
void add_turn_block(CLI::App* sub, int& turn_block);
// --metric PATH: compare, compare-builds, report, history report.
void add_metric(CLI::App* sub, std::string& metric, const std::string& doc);
// --only PATTERN, once or more: the jobs whose id matches (plan/job_selection.h).
CLI::Option* add_only(CLI::App* sub, std::vector<std::string>& patterns, const std::string& doc);

}  // namespace sb::cli
