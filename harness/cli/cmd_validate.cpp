// `shadowbench validate` and `shadowbench plan`: every job planned on the
// CPU, no GL, so a bad scene file is found now, and the counts say which
// jobs will be skipped and why. `plan --json` prints the plan whole, bad
// scenes included (their jobs fail in it), before the exit code says so.
#include <cstdio>
#include <memory>
#include <string>
#include <utility>

#include "cli/command_line.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "cli/shared.h"
#include "config/experiment.h"
#include "core/error.h"
#include "plan/job_selection.h"
#include "plan/plan.h"
#include "plan/plan_json.h"
#include "plan/shards.h"
#include "store/results_store.h"

namespace sb::cli {

using config::Experiment;
using config::TechniqueVariant;
using core::InputError;
using core::kExitBadInput;
using core::kExitInternal;
using core::kExitOk;
using plan::describe_plan;
using plan::describe_shards;
using plan::make_plan;
using plan::Plan;
using plan::plan_to_json;
using plan::PlannedJob;
using plan::ScenePlan;
using plugin::Registry;
using store::json_text;

namespace {

// validate's and plan's.
struct ValidateArgs {
  explicit ValidateArgs(std::string command) : experiment(std::move(command)) {}
  ExperimentArgs experiment;
  int shards = 1;                 // plan: N
  bool plan_json = false;         // plan: the plan as JSON (plan/plan_json.h)
  std::vector<std::string> only;  // plan: job id globs (plan/job_selection.h)
};

int cmd_validate(const ValidateArgs& a, bool show_plan) {
  const Registry r = load_registry(a.experiment.plugins);
  const Experiment e = load_checked_experiment(a.experiment, r);
  const Plan plan = make_plan(e, a.shards);
  const plan::JobSelection only(a.only);
  only.check(plan);
  if (show_plan && !only.all()) {
    std::printf("%s", describe_selection(e, plan, only).c_str());
  } else if (show_plan && a.plan_json) {
    std::printf("%s\n", json_text(plan_to_json(e, plan), 2).c_str());
  } else if (show_plan) {
    std::printf("%s", describe_plan(e, plan).c_str());
    if (a.shards > 1) std::printf("\n%s", describe_shards(plan).c_str());
  }
  for (size_t s = 0; s < plan.scenes.size(); ++s) {
    const ScenePlan& sp = plan.scenes[s];
    if (sp.error.empty()) continue;
    const std::string what =
        sp.bad_input
            ? sp.input_error
            : InputError(e.file, e.scenes[s].pointer, "scene " + e.scenes[s].name + ": " + sp.error,
                         e.scenes[s].position)
                  .what();
    std::fprintf(stderr, "shadowbench: error: %s\n", what.c_str());
    return kExitBadInput;
  }
  // A technique whose plugin failed to load: the config may be right, the
  // environment is not (exit 3, as with no plugins at all).
  for (const TechniqueVariant& tv : e.techniques) {
    if (tv.unavailable.empty()) continue;
    std::fprintf(stderr, "shadowbench: error: %s\n",
                 InputError(e.file, tv.pointer, tv.unavailable, e.position(tv.pointer)).what());
    return kExitInternal;
  }
  if (!show_plan)
    std::printf(
        "%s: ok: %zu scene variant(s) × %zu resolution(s) × %zu technique variant(s) = %zu jobs "
        "(%zu to run, %zu skipped; `shadowbench plan` says why)\n",
        e.file.c_str(), e.scenes.size(), e.resolutions.size(), e.techniques.size(),
        plan.jobs.size(), plan.count(PlannedJob::Status::Run),
        plan.count(PlannedJob::Status::Skip));
  return kExitOk;
}

// CONFIG, --plugins and --max-jobs, which validate and plan both take.
void add_experiment_options(CLI::App* sub, ExperimentArgs& a) {
  add_argument(sub, "CONFIG", a.config, "the experiment (JSON)");
  add_plugins(sub, a.plugins);
  add_max_jobs(sub, a.max_jobs);
}

}  // namespace

void add_validate_command(CommandLine& cl) {
  const auto a = std::make_shared<ValidateArgs>("validate");
  CLI::App* validate = cl.add_command(cl.app(), "validate",
                                      "Check CONFIG and its scenes without rendering: exit 2 "
                                      "naming the file and JSON pointer of the first error.",
                                      "shadowbench validate configs/forest06-spheres.json",
                                      [a] { return cmd_validate(*a, false); });
  add_experiment_options(validate, a->experiment);
}

void add_plan_command(CommandLine& cl) {
  const auto a = std::make_shared<ValidateArgs>("plan");
  CLI::App* plan = cl.add_command(
      cl.app(), "plan", "List every job of CONFIG: to run, or skipped and why. No GL is used.",
      "shadowbench plan configs/scenes.json", [a] { return cmd_validate(*a, true); });
  add_experiment_options(plan, a->experiment);
  plan->add_option("--shards", a->shards,
                   "also lay the jobs out in N shards balanced by estimated cost, as `run` "
                   "runs them one by one")
      ->type_name("N")
      ->check(whole_check(1, 10000, "expected a whole number of shards in [1, 10000]"));
  CLI::Option* json = plan->add_flag("--json", a->plan_json,
                                     "print the plan as JSON instead (every job's outcome, cost "
                                     "and shard; the plan.json `run` writes, docs/results.md)");
  add_only(plan, a->only,
           "list instead the jobs whose id matches this glob (repeat for more), as `run --only` "
           "selects them: each one's outcome, id and technique variant")
      ->excludes(json);
}

}  // namespace sb::cli
