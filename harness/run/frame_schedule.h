#pragma once
// Which frames one job renders, in which order, and what their times make:
// the compile frame (untimed, so that shader compilation and the driver's
// first-use work never land in a timed frame, whatever the warm-up count),
// the warm-up frames, the timed frames, each of these but the compile frame
// next to a control frame in ABBA order (job, control; control, job; ...),
// one more untimed frame of the job when a control frame came last (the
// visibility read back must be the job's), and with --pass-timing fine as
// many frames again as timed, each pass its own bracket (docs/design.md,
// docs/ci.md). The schedule knows nothing of GL: a FrameTarget renders.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "gl/pass_timer.h"
#include "record/timing_record.h"

namespace sb::run {

// What renders the frames: the GL executor's (run/technique_frames.h), or a
// test's fake. Each frame's name is for error messages and the I/O trace.
class FrameTarget {
 public:
  virtual ~FrameTarget() = default;
  virtual gl::PassTimer::Frame job_frame(const std::string& name, gl::PassDetail detail) = 0;
  virtual gl::PassTimer::Frame control_frame(const std::string& name) = 0;
  // Interleaved A/B runs (compare-builds): before each block of timed frames.
  virtual void take_turn() = 0;
};

struct FrameSchedule {
  std::string job;  // the technique variant: frames are named after it
  int warmup_frames = 2;
  int timed_frames = 10;
  std::optional<std::string> control;  // the control's technique variant, if any
  gl::PassDetail pass_detail = gl::PassDetail::Coarse;
  int turn_block_frames = 0;  // timed frames per turn; 0: no turns
  // The record's timing.noise: the threshold its medians' intervals are
  // judged by, the machine's load before the first timed frame and after the
  // last (null: not read), and the CPUs the run may use.
  double noise_threshold = 0.05;
  std::function<std::optional<double>()> load_average;
  std::int64_t usable_cores = 0;
  // frames.timed "auto": timed_frames is the first block and each next one;
  // blocks are added until the median's interval is within `target`, or a
  // bound (record timing.auto).
  struct AutoFrames {
    double target = 0.03;
    int max_frames = 1000;
    double max_seconds = 10;
  };
  std::optional<AutoFrames> auto_frames;
  // Seconds on a monotonic clock (a test's fake may step it); null: the
  // steady clock.
  std::function<double()> clock;
};

// Renders the schedule's frames on `target` and returns their statistics and
// samples (timing.control's ratios included); a frame that throws ends it.
record::TimingRecord time_frames(FrameTarget& target, const FrameSchedule& schedule);

}  // namespace sb::run
