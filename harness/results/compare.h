#pragma once
// `shadowbench compare BASE_DIR NEW_DIR`: did a change make a job slower or
// less accurate? Jobs are matched by job_id. Per job:
//   - time: a two-sided Mann–Whitney U test on the per-frame times
//     (timing.frame.samples_ms, or timing.technique.samples_ms with
//     --timing technique) and the relative change of the medians;
//     a regression is p < alpha AND the new median slower by more than
//     time_threshold (an improvement likewise, faster);
//   - error: the chosen metric (default metrics.visibility.all.rmse); a
//     regression is an increase by more than error_threshold (absolute), an
//     improvement a decrease by more than it.
// A job that was ok in BASE and is failed in NEW is a regression too.
#include <optional>
#include <string>
#include <vector>

#include "record/job_record.h"

namespace sb {

// The exit code of `shadowbench compare` when some job regressed (0: none,
// 2: bad input). Distinct from 1, which `run` uses for failed jobs.
constexpr int kExitRegression = 4;

struct CompareOptions {
  double alpha = 0.05;
  double time_threshold = 0.10;                // relative change of the median frame time
  double error_threshold = 0.005;              // absolute change of the error metric
  std::string metric = "visibility.all.rmse";  // a path under a record's "metrics"
  std::string timing = "frame";  // which samples: "frame" or "technique" (its passes' sum)
};

enum class Verdict { kUnchanged, kRegression, kImprovement, kNotCompared };
const char* to_string(Verdict v);

struct JobComparison {
  std::string job_id;
  std::string base_status, new_status;
  // Time (frame = G-buffer + technique + shading, or the technique alone), in ms.
  size_t base_samples = 0, new_samples = 0;
  double base_median_ms = 0, new_median_ms = 0;
  double change = 0;        // new median / base median - 1
  std::optional<double> p;  // absent without samples on both sides
  Verdict time = Verdict::kNotCompared;
  // Error metric; absent where a record lacks it.
  std::optional<double> base_error, new_error;
  Verdict error = Verdict::kNotCompared;
  std::string note;  // why something was not compared, or a status change
  bool regressed() const;
};

struct CompareResult {
  std::vector<JobComparison> jobs;  // in BASE order, then jobs only in NEW are listed apart
  std::vector<std::string> only_base, only_new;
  int regressions = 0, improvements = 0;  // jobs with any regression / any improvement and none
};

// Throws InputError for an options value out of range or an unknown metric.
void check_options(const CompareOptions& o);
CompareResult compare_runs(const std::vector<JobRecord>& base, const std::vector<JobRecord>& fresh,
                           const CompareOptions& o);
// The table that `shadowbench compare` prints.
std::string format_comparison(const CompareResult& r, const CompareOptions& o);
// A value of a record's metrics by a dotted path ("visibility.all.rmse", or
// "metrics.visibility.all.rmse"); nullopt when the record has no metrics or
// the path names no metric (record/metrics_record.h, MetricPath).
std::optional<double> metric_value(const JobRecord& record, const std::string& dotted_path);

}  // namespace sb
