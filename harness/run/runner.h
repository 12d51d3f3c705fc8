#pragma once
// Runs an experiment: its plan (plan/plan.h, made once and written to the
// run folder as plan.json), job by job in plan order.
// Each job's record is stored as soon as it finishes; a failing job is
// recorded as "failed" and the run goes on. With isolation, jobs render in
// child processes, so that a crash, a hang or an out-of-memory kill fails
// one job instead of the run (docs/robustness.md).
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "config/experiment.h"
#include "core/names.h"
#include "gl/context.h"
#include "gl/pass_timer.h"
#include "plan/job_selection.h"
#include "plan/plan.h"
#include "plan/shards.h"
#include "plugin/registry.h"
#include "record/session_record.h"

namespace sb::run {

// Where jobs render: in this process, in one child process per (scene,
// resolution), or in one child process per job.
enum class Isolation { None, Group, Job };
Isolation isolation_from_string(const std::string& s);  // throws std::invalid_argument
std::string to_string(Isolation isolation);

struct RunOptions {
  std::string run_dir;  // created if missing; an existing one is resumed
  std::string run_id;
  gl::Backend backend = gl::Backend::OSMesa;
  std::string cache_dir = "results/cache";  // reference cache ("" = off)
  bool write_images = true;
  bool write_gbuffer = false;  // also write the G-buffer's positions and normals as EXR
  bool quiet = false;
  // Overrides the experiment's reference.embree_config ("isa=avx2", ...).
  std::string embree_config;
  // Coarse: one timing bracket around each technique. Fine: also time each
  // of its passes, in extra frames that never enter the technique's time.
  gl::PassDetail pass_detail = gl::PassDetail::Coarse;
  // How brackets are timed. Empty: by the context, CPU clocks on software
  // rasterisers, GL timestamps on GPUs (gl/pass_timer.h). Tests set
  // GpuQuery to run the GPUs' path on llvmpipe.
  std::optional<gl::TimingSource> timing_source;
  // Interleaved A/B runs (`compare-builds`, run/take_turns.h): called with
  // the technique variant's name before every block of this many timed
  // frames; it returns when this run may go on. Empty: never waits.
  std::function<void(const std::string& technique_variant)> take_turn;
  int turn_block_frames = 5;
  // None here, for callers that run several experiments in one process (a
  // forked child needs a parent with one thread); the CLI's default is Group.
  Isolation isolation = Isolation::None;
  // Override the config's limits.job_seconds and limits.setup_seconds
  // (enforced only with isolation).
  std::optional<double> job_seconds, setup_seconds;
  // Only this shard's jobs (plan/shards.h); 1/1 runs them all.
  plan::ShardSpec shard;
  // `run --only`: of those, only the selected jobs run. The others' records
  // in the run folder stay as they are, and the reports include them.
  plan::JobSelection only;
  // The command that reruns one job in-process (`run --only ID --isolation
  // none`), for a crashed or hung job's reason; empty: none is suggested.
  std::function<std::string(const std::string& job_id)> reproduce_command;
  // What every record of this run names as its session; unset: a new one
  // when the run starts (run/session_info.h).
  std::optional<record::SessionRecord> session;
  // `run --retime`: a kept ok job is rendered and timed again in this
  // session, its metrics, images and reference kept from its record.
  bool retime = false;
  // The plan's builds of the scenes kept for their jobs (plan::make_plan's
  // keep_bytes); a scene over it is built again to run. Tests lower it.
  size_t keep_scene_bytes = plan::kRunKeptSceneBytes;
};

struct RunSummary {
  int ok = 0;
  int skipped = 0;
  int failed = 0;
  int resumed = 0;      // finished in an earlier run of the same directory
  int retimed = 0;      // finished earlier, timed again (--retime): in ok, not resumed
  int respecified = 0;  // finished earlier, but with other settings: run again
  // Why they ran again (record/spec_changes.h), each with its count of
  // jobs, in the order first met.
  std::vector<std::pair<std::string, int>> rerun_reasons;
  void add_rerun_reason(const std::string& why);
  int bad_input = 0;    // scene variants whose input (a glTF file, say) was bad
  int crashed = 0;      // failed jobs whose process died under them (isolation)
  int timed_out = 0;    // failed jobs killed at their time limit (isolation)
  int bad_records = 0;  // record files of an earlier run that could not be trusted
  int unselected = 0;   // jobs of the shard that --only left out
};

RunSummary run_experiment(const config::Experiment& experiment, const RunOptions& options);

}  // namespace sb::run
