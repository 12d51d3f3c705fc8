#pragma once
// Runs an experiment: scene variants × resolutions × technique variants.
// Each job's record is stored as soon as it finishes; a failing job is
// recorded as "failed" and the run goes on.
#include <functional>
#include <string>

#include "config/experiment.h"
#include "core/names.h"
#include "gl/context.h"
#include "gl/pass_timer.h"
#include "plugin/registry.h"

namespace sb {

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
  // Interleaved A/B runs (`compare-builds`, run/take_turns.h): called with
  // the technique variant's name before every block of this many timed
  // frames; it returns when this run may go on. Empty: never waits.
  std::function<void(const std::string& technique_variant)> take_turn;
  int turn_block_frames = 5;
};

struct RunSummary {
  int ok = 0;
  int skipped = 0;
  int failed = 0;
  int resumed = 0;      // finished in an earlier run of the same directory
  int respecified = 0;  // finished earlier, but with other settings: run again
  int bad_input = 0;    // scene variants whose input (a glTF file, say) was bad
};

RunSummary run_experiment(const Experiment& experiment, const RunOptions& options);

}  // namespace sb
