// `shadowbench compare` (two run folders) and `shadowbench compare-builds`
// (two builds run on one config taking turns, then compared).
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli/command_line.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "cli/shared.h"
#include "core/error.h"
#include "results/compare.h"
#include "run/runner.h"
#include "run/take_turns.h"
#include "store/results_store.h"

namespace sb::cli {

using core::InputError;
using core::kExitBadInput;
using core::kExitInternal;
using core::kExitJobsFailed;
using core::kExitOk;
using record::JobRecord;
using results::check_options;
using results::compare_exit_code;
using results::compare_runs;
using results::CompareOptions;
using results::CompareResult;
using results::format_comparison;
using run::RunOptions;
using run::take_turns;
using run::TurnCommand;
using run::TurnsResult;
using store::read_job_records;

namespace {

int compare_dirs(const std::string& base, const std::string& fresh, const CompareOptions& options) {
  const std::string dirs[2] = {base, fresh};
  std::vector<JobRecord> runs[2];
  for (int i = 0; i < 2; ++i) {
    const std::string& dir = dirs[i];
    if (!std::filesystem::is_directory(dir)) throw InputError(dir, "", "no such run directory");
    runs[i] = read_job_records(dir);
    if (runs[i].empty()) throw InputError(dir + "/results.jsonl", "", "no records");
  }
  const CompareResult r = compare_runs(runs[0], runs[1], options);
  if (r.jobs.empty()) throw InputError(fresh, "", "no job in common with " + base);
  auto describe = [](const std::vector<JobRecord>& records, const std::string& dir) {
    const std::string& id = records[0].run_id;
    return dir + (id.empty() ? "" : " (" + id + ")");
  };
  std::printf("BASE %s\nNEW  %s\n", describe(runs[0], base).c_str(),
              describe(runs[1], fresh).c_str());
  std::printf("%s", format_comparison(r, options).c_str());
  if (r.regressions > 0) std::fprintf(stderr, "shadowbench: %d job(s) regressed\n", r.regressions);
  if (r.time_refused > 0)
    std::fprintf(
        stderr,
        "shadowbench: the time of %d job(s) was not compared (other or unknown hosts, or no "
        "control timing): use --normalize control, or --timing none for errors only\n",
        r.time_refused);
  if (r.error_refused > 0)
    std::fprintf(
        stderr,
        "shadowbench: the error of %d job(s) was not compared (BASE and NEW used different "
        "references; the fields are listed above): use --allow-reference-change to "
        "compare them anyway, or --metric none for times only\n",
        r.error_refused);
  return compare_exit_code(r);
}

struct CompareArgs {
  std::string base_dir, new_dir;
  CompareOptions compare;
};

int cmd_compare(const CompareArgs& a) {
  if (a.base_dir.empty() || a.new_dir.empty())
    throw InputError("", "command line",
                     "expected BASE_DIR NEW_DIR (see shadowbench compare --help)");
  return compare_dirs(a.base_dir, a.new_dir, a.compare);
}

// Both runs time the control next to every frame: their ratios are the
// steadier measure (docs/ci.md, "What the gate catches"), hence
// compare-builds' own default, --normalize control.
CompareOptions ratios_to_the_control() {
  CompareOptions o;
  o.normalize = "control";
  return o;
}

struct CompareBuildsArgs {
  std::string config;
  std::string base_binary, new_binary;
  std::string out;
  int turn_block = RunOptions{}.turn_block_frames;
  ReferenceArgs reference;
  CompareOptions compare = ratios_to_the_control();
};

// Both builds run CONFIG taking turns (run/take_turns.h), each into its own
// folder under --out, then the two are compared as `compare` does.
int cmd_compare_builds(const CompareBuildsArgs& a) {
  if (a.base_binary.empty() || a.new_binary.empty())
    throw InputError("", "command line",
                     "compare-builds needs --base BIN_A and --new BIN_B (see shadowbench "
                     "compare-builds --help)");
  const std::string config = one_config(a.config, "compare-builds");
  for (const std::string* bin : {&a.base_binary, &a.new_binary})
    if (::access(bin->c_str(), X_OK) != 0)
      throw InputError(*bin, "", "not an executable shadowbench binary");
  if (!std::filesystem::is_regular_file(config)) throw InputError(config, "", "no such config");
  check_options(a.compare);
  const std::string out = a.out.empty() ? "results/" + default_run_id("compare-builds") : a.out;
  const std::string dirs[2] = {out + "/base", out + "/new"};
  TurnCommand commands[2];
  for (int i = 0; i < 2; ++i) {
    TurnCommand& c = commands[i];
    c.label = i == 0 ? "base" : "new";
    c.argv = {i == 0 ? a.base_binary : a.new_binary,
              "run",
              config,
              "--out",
              dirs[i],
              "--quiet",
              "--no-images",
              "--turn-block",
              std::to_string(a.turn_block),
              "--backend",
              a.reference.backend};
    if (a.reference.no_cache)
      c.argv.push_back("--no-cache");
    else
      c.argv.insert(c.argv.end(), {"--cache-dir", a.reference.cache_dir});
    if (!a.reference.embree_config.empty())
      c.argv.insert(c.argv.end(), {"--embree-config", a.reference.embree_config});
  }
  std::printf("compare-builds: base %s, new %s, taking turns every %d timed frames\n",
              a.base_binary.c_str(), a.new_binary.c_str(), a.turn_block);
  std::fflush(stdout);
  const TurnsResult t = take_turns(commands[0], commands[1]);
  for (int i = 0; i < 2; ++i) {
    std::printf("%s: %s, %d turns, exit code %d\n", commands[i].label.c_str(), dirs[i].c_str(),
                t.turns[i], t.exit_code[i]);
    // 0: every job ok or skipped; 1: some failed, which compare judges.
    if (t.exit_code[i] != kExitOk && t.exit_code[i] != kExitJobsFailed) {
      std::fprintf(stderr, "shadowbench: the %s build's run failed (exit code %d)\n",
                   commands[i].label.c_str(), t.exit_code[i]);
      return t.exit_code[i] == kExitBadInput ? kExitBadInput : kExitInternal;
    }
  }
  return compare_dirs(dirs[0], dirs[1], a.compare);
}

// compare's options, which compare-builds takes too.
void add_compare_options(CLI::App* sub, CompareOptions& o) {
  sub->add_option("--alpha", o.alpha,
                  "significance level of the Mann-Whitney U test on the frame times")
      ->type_name("A")
      ->check(number_check());
  sub->add_option("--time-threshold", o.time_threshold,
                  "flag a slower median only beyond this relative change (0.10 is 10 %)")
      ->type_name("R")
      ->check(number_check());
  sub->add_option("--error-threshold", o.error_threshold,
                  "flag a larger error only beyond this absolute change")
      ->type_name("E")
      ->check(number_check());
  add_metric(
      sub, o.metric,
      "the error compared: <visibility|shaded>.<geometry|all|penumbra|soft_union|...>.<key>, "
      "or none (times only)");
  add_choice(sub, "--timing", o.timing, {"frame", "technique", "none"},
             "which times: whole frames, the technique's passes, or none (errors only)");
  add_choice(sub, "--normalize", o.normalize, {"none", "control"},
             "compare absolute times (same host only) or each frame's ratio to the control job's");
  add_choice(sub, "--correction", o.correction, {"holm", "bh", "none"},
             "share alpha across the jobs tested: Holm (family-wise), Benjamini-Hochberg, or "
             "none (alpha per job)");
  sub->add_flag("--allow-reference-change", o.allow_reference_change,
                "compare errors also where BASE and NEW used different references (noted)");
}

}  // namespace

void add_compare_command(CommandLine& cl) {
  const auto a = std::make_shared<CompareArgs>();
  CLI::App* compare = cl.add_command(
      cl.app(), "compare",
      "Compare two run folders job by job: exit 4 when a job got significantly slower or less "
      "accurate beyond the thresholds.",
      "shadowbench compare results/baselines/ci results/ci-new --normalize control",
      [a] { return cmd_compare(*a); });
  add_argument(compare, "BASE_DIR", a->base_dir, "the baseline run folder");
  add_argument(compare, "NEW_DIR", a->new_dir, "the run folder to judge");
  add_compare_options(compare, a->compare);
}

void add_compare_builds_command(CommandLine& cl) {
  const auto a = std::make_shared<CompareBuildsArgs>();
  CLI::App* builds = cl.add_command(
      cl.app(), "compare-builds",
      "Run CONFIG with two shadowbench builds taking turns, block of frames by block of "
      "frames, then compare them (the A/B gate for pull requests, docs/ci.md).",
      "shadowbench compare-builds --base ../base/build/shadowbench --new build/shadowbench "
      "configs/ci.json",
      [a] { return cmd_compare_builds(*a); });
  add_argument(builds, "CONFIG", a->config, "the experiment (JSON) both builds run");
  builds->add_option("--base", a->base_binary, "the baseline build's shadowbench")
      ->type_name("BIN");
  builds->add_option("--new", a->new_binary, "the new build's shadowbench")->type_name("BIN");
  builds
      ->add_option("--out", a->out,
                   "where the two runs go, as DIR/base and DIR/new "
                   "(default: results/compare-builds-<UTC time>)")
      ->type_name("DIR");
  add_turn_block(builds, a->turn_block);
  add_reference_options(builds, a->reference);
  add_compare_options(builds, a->compare);
}

}  // namespace sb::cli
