// `shadowbench run`: every job of a config, into a run folder.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/command_line.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "cli/reproduce_command.h"
#include "cli/shared.h"
#include "config/experiment.h"
#include "core/error.h"
#include "gl/pass_timer.h"
#include "plan/job_selection.h"
#include "plan/shards.h"
#include "results/noisy_jobs.h"
#include "results/report.h"
#include "run/runner.h"
#include "run/session_info.h"
#include "run/take_turns.h"
#include "store/results_store.h"

namespace sb::cli {

using config::Experiment;
using core::InputError;
using core::kExitBadInput;
using core::kExitInternal;
using core::kExitJobsFailed;
using core::kExitOk;
using plan::parse_shard;
using plugin::Registry;
using record::JobRecord;
using results::make_markdown;
using results::noise_warning;
using run::Isolation;
using run::isolation_from_string;
using run::run_experiment;
using run::RunOptions;
using run::RunSummary;
using run::TurnTaker;
using store::read_job_records;

namespace {

struct RunArgs {
  ExperimentArgs experiment{"run"};
  std::string out;
  ReferenceArgs reference;
  bool no_images = false, gbuffer = false, quiet = false, retime = false;
  CiOutputs ci;
  std::string pass_timing = "coarse";
  int turn_block = RunOptions{}.turn_block_frames;
  std::string isolation = "group";    // job, group or none
  std::optional<double> job_timeout;  // seconds, over limits.job_seconds
  std::string shard;                  // K/N
  std::string take_turns;             // IN_FD,OUT_FD of compare-builds' turn pipes
  std::vector<std::string> only;      // job id globs (plan/job_selection.h)
};

int cmd_run(const RunArgs& a) {
  // The session starts with the command, before plugins and the config load.
  const record::SessionRecord session = run::start_session();
  const Registry r = load_registry(a.experiment.plugins);
  const Experiment e = load_checked_experiment(a.experiment, r);
  RunOptions o;
  o.backend = gl::backend_from_string(a.reference.backend);
  if (a.out.empty()) {
    o.run_id = default_run_id(e.name);
    o.run_dir = "results/" + o.run_id;
  } else {
    o.run_dir = a.out;
    o.run_id = std::filesystem::path(a.out).lexically_normal().filename().string();
    if (o.run_id.empty())
      o.run_id = std::filesystem::path(a.out).lexically_normal().parent_path().filename().string();
  }
  o.cache_dir = a.reference.no_cache ? "" : a.reference.cache_dir;
  o.write_images = !a.no_images;
  o.write_gbuffer = a.gbuffer;
  o.quiet = a.quiet;
  o.embree_config = a.reference.embree_config;
  o.pass_detail = gl::pass_detail_from_string(a.pass_timing);
  o.turn_block_frames = a.turn_block;
  o.isolation = isolation_from_string(a.isolation);
  if (!a.shard.empty()) o.shard = parse_shard(a.shard);
  o.job_seconds = a.job_timeout;
  o.session = session;
  o.retime = a.retime;
  o.only = plan::JobSelection(a.only);
  o.reproduce_command = [arguments = own_arguments(), dir = o.run_dir](const std::string& id) {
    return arguments.empty() ? std::string() : reproduce_command(arguments, dir, id);
  };
  if (o.isolation == Isolation::None && a.job_timeout)
    std::fprintf(stderr,
                 "shadowbench: warning: --job-timeout is enforced only with --isolation group or "
                 "job; with none a hung job stalls the run\n");
  std::optional<TurnTaker> turns;
  if (!a.take_turns.empty()) {
    turns = TurnTaker::parse(a.take_turns);
    o.take_turn = [&turns](const std::string& what) { turns->take(what); };
  }
  RunSummary s;
  try {
    // In an interleaved A/B run nothing, not even the scene's set-up,
    // overlaps the other build's turn.
    if (turns) turns->take("start");
    s = run_experiment(e, o);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "shadowbench: %s\n", ex.what());
    return kExitInternal;
  }
  const std::vector<JobRecord> records = read_job_records(o.run_dir);
  if (!a.quiet) {
    const auto md = make_markdown(records, e.name + " (" + o.run_id + ")");
    std::printf("\n%s\n", md.c_str());
  }
  // Why finished jobs ran again, even with --quiet: their old numbers are gone.
  for (const auto& [why, count] : s.rerun_reasons)
    std::printf("%d job%s rerun: %s\n", count, count == 1 ? "" : "s", why.c_str());
  std::printf("%d ok, %d skipped, %d failed, %d resumed", s.ok, s.skipped, s.failed, s.resumed);
  if (s.retimed > 0) std::printf(" (%d of the ok re-timed, their errors kept)", s.retimed);
  if (s.crashed + s.timed_out > 0)
    std::printf(" (of the failed, %d crashed and %d timed out)", s.crashed, s.timed_out);
  if (s.unselected > 0) std::printf(" (%d jobs left out by --only)", s.unselected);
  if (s.bad_records > 0)
    std::printf(" (%d earlier record files could not be trusted and were rerun)", s.bad_records);
  if (s.respecified > 0)
    std::printf(" (%d earlier records had other settings and were rerun)", s.respecified);
  std::printf("; results in %s\n", o.run_dir.c_str());
  if (!a.ci.benchmark_out.empty() || !a.ci.bencher_out.empty()) write_ci_outputs(a.ci, records);
  // The last line, even with --quiet: tables that rank noisy times mislead.
  if (const auto warning = noise_warning(records)) {
    std::fflush(stdout);
    std::fprintf(stderr, "shadowbench: %s\n", warning->c_str());
  }
  if (s.bad_input > 0) return kExitBadInput;
  return s.failed > 0 ? kExitJobsFailed : kExitOk;
}

}  // namespace

void add_run_command(CommandLine& cl) {
  const auto a = std::make_shared<RunArgs>();
  CLI::App* run = cl.add_command(cl.app(), "run",
                                 "Render every job of CONFIG, time it, measure it against the "
                                 "reference, and write records, tables and images. Rerun to "
                                 "resume.",
                                 "shadowbench run configs/quick.json --out results/quick",
                                 [a] { return cmd_run(*a); });
  add_argument(run, "CONFIG", a->experiment.config, "the experiment (JSON)");
  run->add_option("--out", a->out, "the run folder (default: results/<name>-<UTC time>)")
      ->type_name("DIR");
  add_reference_options(run, a->reference);
  run->add_flag("--no-images", a->no_images, "write no EXR/PNG images (records and tables only)");
  run->add_flag("--gbuffer", a->gbuffer, "also write each job's G-buffer positions (EXR)");
  add_plugins(run, a->experiment.plugins);
  run->add_flag("--quiet", a->quiet, "no progress line and no table at the end");
  run->add_flag("--retime", a->retime,
                "time the kept ok jobs of an existing run folder again, in this session, keeping "
                "their reference, errors and images: a resumed run's times then come from one "
                "session");
  add_ci_outputs(run, a->ci);
  add_max_jobs(run, a->experiment.max_jobs);
  add_choice(run, "--pass-timing", a->pass_timing, {"coarse", "fine"},
             "fine: extra frames with every pass in its own timing bracket");
  add_turn_block(run, a->turn_block);
  add_choice(run, "--isolation", a->isolation, {"group", "job", "none"},
             "where jobs render: a child process per (scene, resolution), one per job, or this "
             "process (then a crash or a hang ends the run)");
  run->add_option("--job-timeout", a->job_timeout,
                  "kill a job that runs longer and record it as failed (default: the config's "
                  "limits.job_seconds, 1800); needs isolation")
      ->type_name("SECONDS")
      ->check(bounded_check(1, 604800, "expected a number of seconds in [1, 604800]"));
  run->add_option("--shard", a->shard,
                  "run only shard K of N (1 <= K <= N), in the layout `plan` prints; merge the N "
                  "run folders with `merge`")
      ->type_name("K/N")
      ->check(parser_check([](const std::string& text) { (void)parse_shard(text); }));
  add_only(run, a->only,
           "run only the jobs whose id matches this glob (repeat for more); the run folder's "
           "other records stay and the reports include them. `plan --only` lists what it selects");
  run->add_option("--take-turns", a->take_turns, "IN_FD,OUT_FD of compare-builds' turn pipes")
      ->group("");  // internal: compare-builds runs both builds with it
}

}  // namespace sb::cli
