#pragma once
// Each series of a history with the figures a report plots and the steps
// found in them: one time quantity (time.frame_ratio by default:
// comparable across hosts) on the relative scale, and one error metric on
// the absolute scale (errors can be 0), one value per run in run order.
#include <string>
#include <vector>

#include "history/change_points.h"
#include "history/history_db.h"

namespace sb::history {

// The time quantities a report can plot (run_points.h): the frame's time
// over the control's next to it, or this host's milliseconds.
inline constexpr const char* kTimeQuantities[] = {"time.frame_ratio", "time.frame_ms",
                                                  "time.technique_ms"};

struct SeriesHistory {
  SeriesJobs jobs;            // the series and its job in each run
  std::vector<double> time;   // one per run, NaN where the run has no value
  std::vector<double> error;  // likewise
  std::vector<ChangePoint> time_steps, error_steps;
};

struct HistoryQuantities {
  std::string time = "time.frame_ratio";
  std::string error = "metrics.visibility.geometry.rmse";
};

// Every series of `db` (by name) with its values of both quantities and their
// change points (change_points.h's defaults: relative scale for the time,
// absolute for the error). InputError for a time quantity not in
// kTimeQuantities, or an error quantity that is not "metrics." and a metric
// path (record::MetricPath), naming the option.
std::vector<SeriesHistory> series_histories(const HistoryDb& db, const HistoryQuantities& q);

}  // namespace sb::history
