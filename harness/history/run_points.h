#pragma once
// What the history keeps of one run: per job, the series it
// belongs to and its numbers, each named by a quantity:
//   time.frame_ratio   the job's frames over the control's next to them
//                      (timing.control.frame_ratio.median): comparable
//                      across hosts, the default for a history's plots
//   time.frame_ms      timing.frame.median_ms (this host only)
//   time.technique_ms  timing.technique.median_ms (this host only)
//   metrics.<path>     every number under the record's "metrics", by its
//                      dotted path (metrics.visibility.all.rmse, ...)
// A job that did not reach a number has no point for it.
#include <map>
#include <string>
#include <vector>

#include "record/job_record.h"

namespace sb::history {

struct JobPoints {
  std::string job_id;
  // The series across runs: scene variant, resolution and technique
  // variant, as "scene @ resolution / technique".
  std::string series;
  std::string scene_variant, resolution, technique_variant;
  std::string status;                                  // "ok", "skipped", "failed"
  std::string reason;                                  // why skipped or failed
  std::string host_fingerprint, build_fingerprint;     // "" in older records
  std::vector<std::pair<std::string, double>> values;  // (quantity, value), finite only
  // The job's own noise of a time quantity's value: the relative standard
  // error of its median that the 95 % interval of the job's frames implies
  // (half-width / median / 1.96), where it has one (6 frames or more).
  std::map<std::string, double> noise;
};

std::string series_name(const std::string& scene_variant, const std::string& resolution,
                        const std::string& technique_variant);

std::vector<JobPoints> run_points(const std::vector<record::JobRecord>& records);

}  // namespace sb::history
