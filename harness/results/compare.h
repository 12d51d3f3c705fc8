#pragma once
// `shadowbench compare BASE_DIR NEW_DIR`: did a change make a job slower or
// less accurate? Jobs are matched by job_id. Per job:
//   - time: a two-sided Mann–Whitney U test on the per-frame times
//     (timing.frame.samples, or timing.technique.samples with
//     --timing technique) and the relative change of the medians;
//     a regression is p < alpha AND the new median slower by more than
//     time_threshold (an improvement likewise, faster). Absolute times are
//     compared only between equal host fingerprints (record/host_record.h);
//     otherwise the job's time is refused ("not compared"), which the exit
//     code reports (compare_exit_code). With --normalize control the same
//     test runs on the per-frame ratios to the control job, whatever the
//     hosts; --timing none compares no time at all. The p-values of all
//     jobs whose time was tested are adjusted together (--correction, Holm
//     by default; results/multiple_testing.h), so that alpha bounds the
//     chance that unchanged code fails the run, not each job's;
//   - error: the chosen metric (default metrics.visibility.geometry.rmse); a
//     regression is an increase by more than error_threshold (absolute), an
//     improvement a decrease by more than it. Compared whatever the hosts,
//     but only between records of the same reference
//     (results/reference_identity.h): otherwise the job's error is refused
//     ("not compared") unless allow_reference_change; --metric none compares
//     no error at all.
// A job that was ok in BASE and is failed in NEW is a regression too.
#include <optional>
#include <string>
#include <vector>

#include "record/figures.h"
#include "record/job_record.h"

namespace sb::results {

// The exit code of `shadowbench compare` when some job regressed (0: none,
// 2: bad input). Distinct from 1, which `run` uses for failed jobs.
constexpr int kExitRegression = 4;

struct CompareOptions {
  // 0.02 and 0.10: from the false-alarm and detection table in docs/ci.md
  // (bench/ci_gate_trials.py), not chosen by hand.
  double alpha = 0.02;
  double time_threshold = 0.10;    // relative change of the median frame time
  double error_threshold = 0.005;  // absolute change of the error metric
  // A path under "metrics"; "none": times only.
  std::string metric = record::kDefaultErrorMetric;
  // Which samples: "frame", "technique" (its passes' sum) or "none" (errors only).
  std::string timing = "frame";
  // "none": absolute times, same host fingerprint only; "control": the
  // per-frame ratios to timing.control, whatever the hosts.
  std::string normalize = "none";
  // "holm", "bh" or "none": how alpha is shared across the jobs whose time
  // is tested (docs/ci.md, "Many jobs, one alpha").
  std::string correction = "holm";
  // Compare errors also where BASE's and NEW's references differ (noted).
  bool allow_reference_change = false;
};

enum class Verdict { kUnchanged, kRegression, kImprovement, kNotCompared };
const char* to_string(Verdict v);

struct JobComparison {
  std::string job_id;
  std::string base_status, new_status;
  // Time (frame = G-buffer + technique + shading, or the technique alone), in
  // ms; with normalize "control", unitless ratios to the control's frame.
  size_t base_samples = 0, new_samples = 0;
  double base_median_ms = 0, new_median_ms = 0;
  double change = 0;        // new median / base median - 1
  std::optional<double> p;  // absent without samples on both sides
  // p adjusted across the jobs tested (CompareOptions::correction); the
  // verdict compares this one with alpha.
  std::optional<double> p_adjusted;
  Verdict time = Verdict::kNotCompared;
  // The time was not compared because it would mean nothing: other hosts
  // (absolute times), or no control timing (ratios). The note says which.
  bool time_refused = false;
  // Error metric; absent where a record lacks it.
  std::optional<double> base_error, new_error;
  Verdict error = Verdict::kNotCompared;
  // The error was not compared because BASE and NEW were measured against
  // different references (without allow_reference_change).
  bool error_refused = false;
  std::string note;  // why something was not compared, or a status change
  bool regressed() const;
};

// The host (or build) fingerprints of BASE and NEW for some of the jobs.
struct FingerprintPair {
  std::string base, fresh;               // "" for a record without one
  std::vector<std::string> differences;  // `cpu.model: "A" vs "B"`; none when equal
  int jobs = 0;                          // jobs compared with this pair
  bool same() const { return !base.empty() && base == fresh; }
};

// The jobs whose BASE and NEW references differ in the same fields.
struct ReferenceDifference {
  std::vector<std::string> differences;  // `spp: "64" vs "256"`
  std::vector<std::string> jobs;
};

// A technique whose plugin module differs between BASE and NEW (its
// SHA-256): shown, not refused, since comparing two builds of a plugin is
// what compare is for.
struct PluginDifference {
  std::string technique;
  record::PluginRecord base, fresh;
};

struct CompareResult {
  std::vector<JobComparison> jobs;  // in BASE order, then jobs only in NEW are listed apart
  std::vector<std::string> only_base, only_new;
  int regressions = 0, improvements = 0;  // jobs with any regression / any improvement and none
  int time_refused = 0;                   // jobs whose time was refused (time_refused)
  int error_refused = 0;                  // jobs whose error was refused (error_refused)
  int time_tests = 0;                     // jobs whose time was tested: the correction's family
  // Of the jobs ok on both sides whose errors were looked at, those whose
  // references differ, grouped by what differs; and how many had no cache
  // key on either side (so that only the other fields could be checked).
  std::vector<ReferenceDifference> references;
  int references_without_key = 0;
  // Of the jobs ok on both sides, each distinct pair of fingerprints.
  std::vector<FingerprintPair> hosts, builds;
  // Of the jobs on both sides whose records name their plugin, each
  // technique whose plugin's hash differs, once, in the order met.
  std::vector<PluginDifference> plugins;
};

// The exit code of `shadowbench compare` for a result: kExitRegression when
// some job regressed; else 2 (kExitBadInput) when some job's time or error
// was refused, so that a gate that could not judge is not green (use
// --normalize control, or --timing none to judge errors only; for errors
// across references, --allow-reference-change, or --metric none to judge
// times only); else 0.
int compare_exit_code(const CompareResult& r);

// Throws InputError for an options value out of range or an unknown metric.
void check_options(const CompareOptions& o);
// Throws InputError, besides check_options, when a job's BASE and NEW used
// different control techniques under normalize "control".
CompareResult compare_runs(const std::vector<record::JobRecord>& base,
                           const std::vector<record::JobRecord>& fresh, const CompareOptions& o);
// The table that `shadowbench compare` prints.
std::string format_comparison(const CompareResult& r, const CompareOptions& o);
// A value of a record's metrics by a dotted path ("visibility.all.rmse", or
// "metrics.visibility.all.rmse"); nullopt when the record has no metrics or
// the path names no metric (record/metrics_record.h, MetricPath).
std::optional<double> metric_value(const record::JobRecord& record, const std::string& dotted_path);

}  // namespace sb::results
