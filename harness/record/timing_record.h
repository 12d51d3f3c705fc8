#pragma once
// record["timing"]: how a job's frames were timed, and what they measured
// (docs/results.md, "timing").
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "record/fields.h"

namespace sb {

// One timed series: its statistics and every sample, in frame order
// ({count, median_ms, p10_ms, p90_ms, mean_ms, min_ms, max_ms, cv, samples_ms}).
struct TimingSeries {
  std::int64_t count = 0;
  double median_ms = 0, p10_ms = 0, p90_ms = 0, mean_ms = 0, min_ms = 0, max_ms = 0;
  double cv = 0;  // population standard deviation / mean
  std::vector<double> samples_ms;

  // The statistics of `samples` (record/timing_stats.h), which are kept too.
  static TimingSeries of(const std::vector<double>& samples);
  nlohmann::json to_json() const;
  static TimingSeries from_json(const Fields& f);
};

// Per-pass detail, from frames of their own (`run --pass-timing fine`):
// written as timing.passes, timing.pass_order and timing.fine.
struct FineTiming {
  std::vector<std::string> pass_order;         // as the technique first named them
  std::map<std::string, TimingSeries> passes;  // by name
  int frames = 0;                              // timed fine frames
  TimingSeries technique;                      // the sum of the passes per frame
  TimingSeries frame;
};

// Unitless per-frame ratios (a job's frame time over the control's next to
// it): the statistics of TimingSeries without the unit
// ({count, median, p10, p90, mean, min, max, cv, samples}).
struct RatioSeries {
  std::int64_t count = 0;
  double median = 0, p10 = 0, p90 = 0, mean = 0, min = 0, max = 0;
  double cv = 0;
  std::vector<double> samples;

  static RatioSeries of(const std::vector<double>& samples);
  nlohmann::json to_json() const;
  static RatioSeries from_json(const Fields& f);
};

// The control job's frames, each timed next to one of the job's (in ABBA
// order), in the same run: timing.control. A job's time as a ratio to the
// control's cancels most of what the machine adds to every frame alike
// (its CPU, llvmpipe's vector width and threads), so ratios compare across
// machines where absolute times cannot (docs/ci.md).
struct ControlTiming {
  std::string technique;    // the control's technique variant, "none" by default
  TimingSeries frame;       // its frames, samples_ms[i] timed next to the job's frame i
  RatioSeries frame_ratio;  // job frame i / control frame i

  nlohmann::json to_json() const;
  static ControlTiming from_json(const Fields& f);
};

struct TimingRecord {
  int compile_frames = 1;  // untimed: shader compilation and first use
  int warmup_frames = 0;
  int timed_frames = 0;
  std::string pass_timing = "coarse";          // "coarse" or "fine"
  TimingSeries frame;                          // G-buffer + technique + shading
  TimingSeries technique;                      // one bracket around all the technique's passes
  std::map<std::string, TimingSeries> shared;  // "gbuffer", "shading"
  std::optional<FineTiming> fine;              // with pass_timing "fine" only
  std::optional<ControlTiming> control;        // unless the config's frames.control is null

  nlohmann::json to_json() const;
  static TimingRecord from_json(const Fields& f);
};

}  // namespace sb
