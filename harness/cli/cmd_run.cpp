// `shadowbench run`: every job of a config, into a run folder.
#include <cstdio>
#include <filesystem>
#include <optional>

#include "cli/commands.h"
#include "config/experiment.h"
#include "core/error.h"
#include "gl/pass_timer.h"
#include "plan/shards.h"
#include "results/report.h"
#include "results/store.h"
#include "run/runner.h"
#include "run/take_turns.h"

namespace sb::cli {

using config::Experiment;
using core::InputError;
using core::kExitBadInput;
using core::kExitInternal;
using core::kExitJobsFailed;
using core::kExitOk;
using plan::parse_shard;
using plugin::Registry;
using results::make_markdown;
using results::read_job_records;
using run::Isolation;
using run::isolation_from_string;
using run::run_experiment;
using run::RunOptions;
using run::RunSummary;
using run::TurnTaker;

int cmd_run(const Args& a) {
  const Registry r = load_registry(a);
  const Experiment e = load_checked_experiment(a, r);
  RunOptions o;
  o.backend = gl::backend_from_string(a.backend);
  if (a.out.empty()) {
    o.run_id = default_run_id(e.name);
    o.run_dir = "results/" + o.run_id;
  } else {
    o.run_dir = a.out;
    o.run_id = std::filesystem::path(a.out).lexically_normal().filename().string();
    if (o.run_id.empty())
      o.run_id = std::filesystem::path(a.out).lexically_normal().parent_path().filename().string();
  }
  o.cache_dir = a.no_cache ? "" : a.cache_dir;
  o.write_images = !a.no_images;
  o.write_gbuffer = a.gbuffer;
  o.quiet = a.quiet;
  o.embree_config = a.embree_config;
  o.pass_detail = gl::pass_detail_from_string(a.pass_timing);
  o.turn_block_frames = a.turn_block;
  o.isolation = isolation_from_string(a.isolation);
  if (!a.shard.empty()) o.shard = parse_shard(a.shard);
  o.job_seconds = a.job_timeout;
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
  if (!a.quiet) {
    const auto md = make_markdown(read_job_records(o.run_dir), e.name + " (" + o.run_id + ")");
    std::printf("\n%s\n", md.c_str());
  }
  // Why finished jobs ran again, even with --quiet: their old numbers are gone.
  for (const auto& [why, count] : s.rerun_reasons)
    std::printf("%d job%s rerun: %s\n", count, count == 1 ? "" : "s", why.c_str());
  std::printf("%d ok, %d skipped, %d failed, %d resumed", s.ok, s.skipped, s.failed, s.resumed);
  if (s.crashed + s.timed_out > 0)
    std::printf(" (of the failed, %d crashed and %d timed out)", s.crashed, s.timed_out);
  if (s.bad_records > 0)
    std::printf(" (%d earlier record files could not be trusted and were rerun)", s.bad_records);
  if (s.respecified > 0)
    std::printf(" (%d earlier records had other settings and were rerun)", s.respecified);
  std::printf("; results in %s\n", o.run_dir.c_str());
  if (!a.benchmark_out.empty() || !a.bencher_out.empty())
    write_ci_outputs(a, read_job_records(o.run_dir));
  if (s.bad_input > 0) return kExitBadInput;
  return s.failed > 0 ? kExitJobsFailed : kExitOk;
}

}  // namespace sb::cli
