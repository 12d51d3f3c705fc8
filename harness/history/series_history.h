#pragma once
// Each series of a history with the figures a report plots and the steps
// found in them: one time quantity (time.frame_ratio by default:
// comparable across hosts) on the relative scale, and one error metric on
// the absolute scale (errors can be 0), one value per run in run order.
#include <string>
#include <vector>

#include "history/change_points.h"
#include "history/history_db.h"
#include "record/figures.h"

namespace sb::history {

struct SeriesHistory {
  SeriesJobs jobs;                 // the series and its job in each run
  std::vector<double> time;        // one per run, NaN where the run has no value
  std::vector<double> time_noise;  // each run's own noise of its time, NaN: unknown
  std::vector<double> error;       // likewise
  std::vector<ChangePoint> time_steps, error_steps;
  // What the detector saw in the time: its noise between runs (sigma, log
  // units on the relative scale), the serial correlation it corrected for,
  // and the runs it took as loaded (one per run).
  double time_sigma = 0, time_serial_correlation = 0;
  std::vector<bool> time_loaded;
};

struct HistoryQuantities {
  std::string time = "time.frame_ratio";
  std::string error = std::string("metrics.") + record::kDefaultErrorMetric;
};

// Every series of `db` (by name) with its values of both quantities and their
// change points (change_points.h's defaults: relative scale for the time,
// absolute for the error). InputError for a time quantity not among the
// catalogue's time series (record/figures.h), or an error quantity that is not "metrics." and a
// metric path (record::MetricPath), naming the option.
std::vector<SeriesHistory> series_histories(const HistoryDb& db, const HistoryQuantities& q);

}  // namespace sb::history
