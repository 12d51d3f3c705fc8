#pragma once
// record["timing"]: how a job's frames were timed, and what they measured
// (docs/results.md, "timing").
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "record/describe.h"
#include "record/fields.h"

namespace sb::record {

// One series of per-frame figures: its statistics and every sample, in frame
// order. A timing series (milliseconds) writes its keys with the suffix
// "_ms" ({count, median_ms, ..., samples_ms}); a ratio series (a job's frame
// over the control's next to it, unitless) without ({count, median, ...}).
struct Series {
  static constexpr RecordDoc kSchema{
      "Series",
      "one series of per-frame figures; keys marked † take the series' unit as a suffix "
      "(`median_ms` in a timing series, `median` in a ratio series)"};

  std::int64_t count = 0;
  double median = 0, p10 = 0, p90 = 0, mean = 0, min = 0, max = 0;
  double cv = 0;  // population standard deviation / mean
  std::vector<double> samples;

  // The statistics of `samples` (record/timing_stats.h), which are kept too.
  static Series of(const std::vector<double>& samples);

  template <class V>
  static void describe(V& v) {
    v.field("count", &Series::count, {"", "samples"});
    v.field("median", &Series::median, {"", "median", Presence::Natural, true});
    v.field("p10", &Series::p10, {"", "10th percentile (numpy's linear)", Presence::Natural, true});
    v.field("p90", &Series::p90, {"", "90th percentile", Presence::Natural, true});
    v.field("mean", &Series::mean, {"", "mean", Presence::Natural, true});
    v.field("min", &Series::min, {"", "least sample", Presence::Natural, true});
    v.field("max", &Series::max, {"", "greatest sample", Presence::Natural, true});
    v.field("cv", &Series::cv, {"", "population standard deviation / mean"});
    v.field("samples", &Series::samples,
            {"", "every sample, in frame order", Presence::Natural, true});
  }
};

// Per-pass detail, from frames of their own (`run --pass-timing fine`):
// written as timing.passes, timing.pass_order and timing.fine.
struct FineTiming {
  static constexpr RecordDoc kSchema{"FineTiming", ""};

  std::vector<std::string> pass_order;   // as the technique first named them
  std::map<std::string, Series> passes;  // by name
  int frames = 0;                        // timed fine frames
  Series technique;                      // the sum of the passes per frame
  Series frame;

  template <class V>
  static void describe(V& v) {
    v.field("passes", &FineTiming::passes,
            {"ms",
             "with `pass_timing` fine: each named pass, from frames in which every pass is "
             "its own bracket"});
    v.field("pass_order", &FineTiming::pass_order,
            {"", "with `pass_timing` fine: the passes, as the technique first named them"});
    v.object("fine", {"", "with `pass_timing` fine: the extra frames' own figures"}, [](auto& sub) {
      sub.field("frames", &FineTiming::frames, {"", "timed fine frames"});
      sub.field("technique", &FineTiming::technique,
                {"ms",
                 "the sum of the passes per frame: against `technique`, what the "
                 "per-pass syncs cost"});
      sub.field("frame", &FineTiming::frame, {"ms", "the fine frames"});
    });
  }
  // pass_order and passes name the same passes.
  static void check(const FineTiming& t, const Fields& f);
};

// The control job's frames, each timed next to one of the job's (in ABBA
// order), in the same run: timing.control. A job's time as a ratio to the
// control's cancels most of what the machine adds to every frame alike
// (its CPU, llvmpipe's vector width and threads), so ratios compare across
// machines where absolute times cannot (docs/ci.md).
struct ControlTiming {
  static constexpr RecordDoc kSchema{
      "ControlTiming",
      "the control job's frames, each timed next to one of the job's, in ABBA order "
      "(config `frames.control`): what `compare --normalize control` tests"};

  std::string technique;  // the control's technique variant, "none" by default
  Series frame;           // its frames, samples[i] timed next to the job's frame i
  Series frame_ratio;     // job frame i / control frame i

  template <class V>
  static void describe(V& v) {
    v.field("technique", &ControlTiming::technique,
            {"", "the control's technique variant, `none` by default"});
    v.field("frame", &ControlTiming::frame,
            {"ms",
             "the control's frames; `samples_ms[i]` was timed next to "
             "`timing.frame.samples_ms[i]`"});
    v.field("frame_ratio", &ControlTiming::frame_ratio,
            {"", "job frame i / control frame i, unitless"});
  }
};

struct TimingRecord {
  static constexpr RecordDoc kSchema{"TimingRecord",
                                     "how the job's frames were timed, and what they took"};

  int compile_frames = 1;  // untimed: shader compilation and first use
  int warmup_frames = 0;
  int timed_frames = 0;
  std::string pass_timing = "coarse";    // "coarse" or "fine"
  Series frame;                          // G-buffer + technique + shading
  Series technique;                      // one bracket around all the technique's passes
  std::map<std::string, Series> shared;  // "gbuffer", "shading"
  std::optional<FineTiming> fine;        // with pass_timing "fine" only
  std::optional<ControlTiming> control;  // unless the config's frames.control is null

  template <class V>
  static void describe(V& v) {
    v.field("compile_frames", &TimingRecord::compile_frames,
            {"", "untimed first frames: shader compilation and first use"});
    v.field("warmup_frames", &TimingRecord::warmup_frames, {"", "untimed warm-up frames"});
    v.field("timed_frames", &TimingRecord::timed_frames, {"", "timed frames"});
    v.field("pass_timing", &TimingRecord::pass_timing,
            {"", "`coarse`, or `fine` with `run --pass-timing fine`"});
    v.field("frame", &TimingRecord::frame,
            {"ms", "the whole frame: G-buffer restore + technique + shading"});
    v.field("technique", &TimingRecord::technique,
            {"ms", "one bracket around all the technique's passes"});
    v.field("shared", &TimingRecord::shared,
            {"ms",
             "the frame's parts every technique shares: `gbuffer` (the restore of the "
             "G-buffer's depth-stencil), `shading`",
             Presence::UnlessEmpty});
    v.flatten(&TimingRecord::fine, {"", "with `pass_timing` fine"});
    v.field("control", &TimingRecord::control,
            {"", "when the run timed a control job next to the job's frames"});
  }
  // The control's frames pair with the job's.
  static void check(const TimingRecord& t, const Fields& f);

  nlohmann::json to_json() const;
  static TimingRecord from_json(const Fields& f);
};

}  // namespace sb::record
