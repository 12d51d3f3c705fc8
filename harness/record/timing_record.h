#pragma once
// record["timing"]: how a job's frames were timed, and what they measured
// (docs/results.md, "timing").
#include <algorithm>
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
  // The median's 95 % interval from order statistics, distribution-free
  // (record/median_interval.h): its ends, its half-width relative to the
  // median, and its coverage (below 0.95 with fewer than 6 samples, where
  // it is the sample range).
  double median_ci_lo = 0, median_ci_hi = 0, median_ci_rel = 0, median_ci_coverage = 0;
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
    v.field("median_ci_lo", &Series::median_ci_lo,
            {"",
             "the median's 95 % confidence interval, distribution-free, from order statistics: "
             "x_(j) of the sorted samples, j the largest rank with P(B ≤ j − 1) ≤ 2.5 %, "
             "B ~ Binomial(count, ½); with fewer than 6 samples no such j exists and the "
             "interval is the sample range (see `median_ci_coverage`)",
             Presence::OlderLack, true});
    v.field("median_ci_hi", &Series::median_ci_hi,
            {"", "its upper end, x_(count + 1 − j)", Presence::OlderLack, true});
    v.field("median_ci_rel", &Series::median_ci_rel,
            {"",
             "its half-width relative to the median, (hi − lo) / 2 / median: 0.05 reads "
             "\"±5 %\"",
             Presence::OlderLack});
    v.field("median_ci_coverage", &Series::median_ci_coverage,
            {"",
             "how often such an interval holds the median, 1 − 2 P(B ≤ j − 1): at least "
             "0.95; below it with fewer than 6 samples (0.9375 at 5, 0.75 at 3, 0 at 1)",
             Presence::OlderLack});
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

struct TimingRecord;

// Whether the job's timings were noisy on this run's machine: the 95 %
// intervals of its medians against the config's `frames.noise_threshold`,
// and the machine's load while its frames were timed (timing.noise). The
// tables, the console and the run's last line mark a noisy job: its median,
// and so its place in a ranking, is not pinned down by its frames.
struct NoiseRecord {
  static constexpr RecordDoc kSchema{
      "NoiseRecord",
      "whether the job's times were noisy: the half-widths of its medians' 95 % intervals "
      "(`median_ci_rel` of its series) against `frames.noise_threshold`, and the machine's "
      "load while its frames were timed"};

  double frame_ci_rel = 0;                     // timing.frame.median_ci_rel
  std::optional<double> control_frame_ci_rel;  // timing.control.frame's
  std::optional<double> frame_ratio_ci_rel;    // timing.control.frame_ratio's
  double threshold = 0;
  bool noisy = false;
  std::optional<double> load_average_start, load_average_end;  // 1-minute, /proc/loadavg
  std::int64_t usable_cores = 0;

  // The judgement of `t`'s series against `threshold`: noisy when the frame's
  // interval or the frame ratio's is wider. The load and cores are the
  // caller's to fill.
  static NoiseRecord judge(const TimingRecord& t, double threshold);
  // The wider of the judged half-widths, frame and frame ratio: what decides
  // `noisy`, and what the console and the tables print.
  double judged_ci_rel() const { return std::max(frame_ci_rel, frame_ratio_ci_rel.value_or(0.0)); }

  template <class V>
  static void describe(V& v) {
    v.field("frame_ci_rel", &NoiseRecord::frame_ci_rel,
            {"", "`timing.frame.median_ci_rel`: the frame time median's relative half-width"});
    v.field("control_frame_ci_rel", &NoiseRecord::control_frame_ci_rel,
            {"",
             "with a control: `timing.control.frame.median_ci_rel`, the control's own frames' "
             "(the machine's noise, whatever the technique); not judged"});
    v.field("frame_ratio_ci_rel", &NoiseRecord::frame_ratio_ci_rel,
            {"", "with a control: `timing.control.frame_ratio.median_ci_rel`"});
    v.field("threshold", &NoiseRecord::threshold,
            {"", "`frames.noise_threshold` of the run: the widest relative half-width not noisy"});
    v.field("noisy", &NoiseRecord::noisy,
            {"", "`frame_ci_rel` or `frame_ratio_ci_rel` is above `threshold`"});
    v.field("load_average_start", &NoiseRecord::load_average_start,
            {"",
             "the 1-minute load average (/proc/loadavg) before the first timed frame; absent "
             "where the system does not say"});
    v.field("load_average_end", &NoiseRecord::load_average_end,
            {"", "the same after the last timed frame"});
    v.field("usable_cores", &NoiseRecord::usable_cores,
            {"", "the CPUs the run may use (its affinity mask): the load to read it against"});
  }
};

// With `frames.timed` "auto": how many frames were timed and why no more
// (timing.auto). Blocks of `block` frames are timed until the wider of the
// frame's and the frame ratio's median intervals (NoiseRecord's judged
// half-width) is within `target`, or a bound is reached.
struct AutoFramesRecord {
  static constexpr RecordDoc kSchema{
      "AutoFramesRecord",
      "with `frames.timed` \"auto\": the frames chosen by the data, and why they stopped"};

  double target = 0;  // frames.auto_target
  int block = 0;      // frames added at a time (frames.auto_block)
  int max_frames = 0;
  double max_seconds = 0;
  std::string stop;       // "target", "max_frames" or "max_seconds"
  double half_width = 0;  // the judged half-width when it stopped
  double seconds = 0;     // the timed frames' wall time

  template <class V>
  static void describe(V& v) {
    v.field("target", &AutoFramesRecord::target,
            {"", "`frames.auto_target`: the relative half-width aimed at"});
    v.field("block", &AutoFramesRecord::block, {"", "frames timed between two looks"});
    v.field("max_frames", &AutoFramesRecord::max_frames, {"", "`frames.auto_max_frames`"});
    v.field("max_seconds", &AutoFramesRecord::max_seconds, {"", "`frames.auto_max_seconds`"});
    v.field("stop", &AutoFramesRecord::stop,
            {"",
             "why no more frames: `target` (the interval was within it), `max_frames` or "
             "`max_seconds` (a bound came first: the job is likely noisy)"});
    v.field("half_width", &AutoFramesRecord::half_width,
            {"",
             "the wider of the frame's and the frame ratio's median half-widths when it "
             "stopped"});
    v.field("seconds", &AutoFramesRecord::seconds,
            {"s", "wall time from the first timed frame to the last"});
  }
};

struct TimingRecord {
  static constexpr RecordDoc kSchema{"TimingRecord",
                                     "how the job's frames were timed, and what they took"};

  int compile_frames = 1;  // untimed: shader compilation and first use
  int warmup_frames = 0;
  int timed_frames = 0;
  std::string pass_timing = "coarse";           // "coarse" or "fine"
  Series frame;                                 // G-buffer + technique + shading
  Series technique;                             // one bracket around all the technique's passes
  std::map<std::string, Series> shared;         // "gbuffer", "shading"
  std::optional<FineTiming> fine;               // with pass_timing "fine" only
  std::optional<ControlTiming> control;         // unless the config's frames.control is null
  std::optional<NoiseRecord> noise;             // absent from older records
  std::optional<AutoFramesRecord> auto_frames;  // with frames.timed "auto"

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
    v.field("noise", &TimingRecord::noise,
            {"", "whether the times were noisy (below, `NoiseRecord`); absent in older records"});
    v.field("auto", &TimingRecord::auto_frames,
            {"", "with `frames.timed` \"auto\": how the timed frames were chosen"});
  }
  // The control's frames pair with the job's.
  static void check(const TimingRecord& t, const Fields& f);

  nlohmann::json to_json() const;
  static TimingRecord from_json(const Fields& f);
};

}  // namespace sb::record
