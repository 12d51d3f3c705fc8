#include "run/frame_schedule.h"

#include <chrono>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "run/io_trace.h"

namespace sb::run {

using record::AutoFramesRecord;
using record::ControlTiming;
using record::FineTiming;
using record::NoiseRecord;
using record::Series;
using record::TimingRecord;

namespace {

// Per-frame times of a run of frames, by bracket.
struct FrameSamples {
  std::vector<double> frame, technique;
  std::map<std::string, std::vector<double>> passes, shared;
  std::vector<std::string> pass_order;

  void add(const gl::PassTimer::Frame& f) {
    frame.push_back(f.total_ms);
    double tech = 0.0;
    for (const auto& [name, ms] : f.passes) {
      if (name.rfind("shared:", 0) == 0) {
        shared[name.substr(7)].push_back(ms);
        continue;
      }
      if (name != "technique" && !passes.count(name)) pass_order.push_back(name);
      if (name != "technique") passes[name].push_back(ms);
      tech += ms;
    }
    technique.push_back(tech);
  }
};

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The half-width the noise judgement would read off these frames: the
// wider of the frame's and the frame ratio's (NoiseRecord::judged_ci_rel).
double judged_half_width(const std::vector<double>& frame, const std::vector<double>& control) {
  TimingRecord t;
  t.frame = Series::of(frame);
  if (!control.empty()) {
    std::vector<double> ratio(control.size());
    for (size_t k = 0; k < ratio.size(); ++k) ratio[k] = frame[k] / control[k];
    t.control = ControlTiming{};
    t.control->frame_ratio = Series::of(ratio);
  }
  return NoiseRecord::judge(t, 0).judged_ci_rel();
}

}  // namespace

TimingRecord time_frames(FrameTarget& target, const FrameSchedule& s) {
  const std::string& name = s.job;
  const bool control = s.control.has_value();
  const bool fine_detail = s.pass_detail == gl::PassDetail::Fine;
  FrameSamples coarse, fine;
  std::vector<double> control_ms;
  const bool tracing = io_trace_enabled();
  std::vector<TraceSpan> trace;  // SHADOWBENCH_IO_TRACE (run/io_trace.h)
  const auto frame_name = [&](int i) {
    return name + (i < 0 ? std::string(" compile frame") : " frame " + std::to_string(i));
  };
  const auto control_frame = [&](int i) {
    return target.control_frame("control " + *s.control + " next to " + frame_name(i));
  };
  // With auto frames, the timed frames grow a block at a time until the
  // data say stop; otherwise the schedule's count.
  int frames = s.warmup_frames + s.timed_frames;
  const auto clock = s.clock ? s.clock : steady_seconds;
  std::optional<AutoFramesRecord> chosen;
  if (s.auto_frames) {
    chosen = AutoFramesRecord{};
    chosen->target = s.auto_frames->target;
    chosen->block = s.timed_frames;
    chosen->max_frames = s.auto_frames->max_frames;
    chosen->max_seconds = s.auto_frames->max_seconds;
  }
  double timed_start = 0;
  const auto load = [&]() { return s.load_average ? s.load_average() : std::nullopt; };
  std::optional<double> load_start;
  // Frame -1 is never timed, whatever the warm-up count: with "warmup": 0
  // compilation would land in a timed frame, and only for the techniques
  // compiled last.
  for (int i = -1; i < frames; ++i) {
    const bool timed = i >= s.warmup_frames;
    if (i == s.warmup_frames) {
      load_start = load();
      timed_start = clock();
    }
    if (timed && s.turn_block_frames > 0 && (i - s.warmup_frames) % s.turn_block_frames == 0)
      target.take_turn();
    const bool control_first = control && i >= 0 && i % 2 == 1;
    gl::PassTimer::Frame before{}, after{};
    const std::int64_t began = tracing ? monotonic_ns() : 0;
    if (control_first) before = control_frame(i);
    const auto frame = target.job_frame(frame_name(i), gl::PassDetail::Coarse);
    if (control && i >= 0 && !control_first) after = control_frame(i);
    if (!timed) continue;
    if (tracing) trace.push_back({"timed", frame_name(i), began, monotonic_ns()});
    coarse.add(frame);
    if (control) control_ms.push_back((control_first ? before : after).total_ms);
    // At the end of a block: stop, or time one more.
    const int timed_so_far = i - s.warmup_frames + 1;
    if (chosen && i + 1 == frames && timed_so_far % chosen->block == 0) {
      chosen->half_width = judged_half_width(coarse.frame, control_ms);
      chosen->seconds = clock() - timed_start;
      if (chosen->half_width <= chosen->target)
        chosen->stop = "target";
      else if (timed_so_far + chosen->block > chosen->max_frames)
        chosen->stop = "max_frames";
      else if (chosen->seconds >= chosen->max_seconds)
        chosen->stop = "max_seconds";
      else
        frames += chosen->block;
    }
  }
  const int timed_frames = frames - s.warmup_frames;
  const std::optional<double> load_end = load();
  // The visibility read back after the frames must be the job's: when a
  // control frame came last, one more untimed frame of the job.
  if (control && !fine_detail && frames > 0 && (frames - 1) % 2 == 0)
    target.job_frame(name + " readback frame", gl::PassDetail::Coarse);
  // Per-pass detail in frames of its own, so its syncs never reach the
  // technique's time above.
  if (fine_detail)
    for (int i = 0; i < timed_frames; ++i) {
      const std::int64_t began = tracing ? monotonic_ns() : 0;
      const std::string fine_name = name + " fine frame " + std::to_string(i);
      fine.add(target.job_frame(fine_name, gl::PassDetail::Fine));
      if (tracing) trace.push_back({"timed", fine_name, began, monotonic_ns()});
    }
  // The test-only trace, written once the frames are done.
  write_trace(trace);

  // Statistics plus the raw per-frame samples, in frame order: comparisons
  // between runs test the samples themselves (shadowbench compare).
  TimingRecord t;
  t.compile_frames = 1;
  t.warmup_frames = s.warmup_frames;
  t.timed_frames = timed_frames;
  t.pass_timing = gl::to_string(s.pass_detail);
  t.frame = Series::of(coarse.frame);
  t.technique = Series::of(coarse.technique);
  for (const auto& [pass, v] : coarse.shared) t.shared[pass] = Series::of(v);
  if (fine_detail) {
    FineTiming detail;
    detail.pass_order = fine.pass_order;
    for (const auto& pass : fine.pass_order) detail.passes[pass] = Series::of(fine.passes[pass]);
    // The same frames' sums: what per-pass syncs cost, against "technique".
    detail.frames = timed_frames;
    detail.technique = Series::of(fine.technique);
    detail.frame = Series::of(fine.frame);
    t.fine = std::move(detail);
  }
  if (control) {
    ControlTiming c;
    c.technique = *s.control;
    c.frame = Series::of(control_ms);
    std::vector<double> ratio(control_ms.size());
    for (size_t k = 0; k < ratio.size(); ++k) ratio[k] = coarse.frame[k] / control_ms[k];
    c.frame_ratio = Series::of(ratio);
    t.control = std::move(c);
  }
  t.noise = NoiseRecord::judge(t, s.noise_threshold);
  t.noise->load_average_start = load_start;
  t.noise->load_average_end = load_end;
  t.noise->usable_cores = s.usable_cores;
  t.auto_frames = std::move(chosen);
  return t;
}

}  // namespace sb::run
