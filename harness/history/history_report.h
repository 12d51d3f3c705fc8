#pragma once
// `shadowbench history report`: a history of runs (history_db.h) as a static
// site that works offline:
//   index.html   every step found, newest first; a table of every series
//                (scene, resolution, technique variant) with its latest time
//                and error, a sparkline of each with its steps marked, and
//                the number of steps; the runs and the hosts they ran on
//   series/<job id>.html   one page per series: time and error against run
//                (commit) order, drawn by matplotlib (plot_charts.py, kind
//                "history"), each host with its own marker, each segment's
//                median and each step drawn; every step with the last run
//                before it and the first after it, linked to those runs'
//                folders, reports and images where they are on this machine
//   steps.json   the same steps for scripts (a CI job that wants to fail on
//                a new step reads it)
// Times are the frame's time over the control's (time.frame_ratio) unless
// asked otherwise; a page of milliseconds across hosts says so in a banner.
#include <string>
#include <vector>

#include "history/history_db.h"
#include "history/series_history.h"

namespace sb::history {

struct HistoryReportOptions {
  HistoryQuantities quantities;
  std::string title = "shadowbench history";
};

struct ReportedStep {
  std::string series, quantity, commit, previous_commit, page;
  std::int64_t run_order = 0;  // the first run after the step
  ChangePoint change;
};

struct HistoryReport {
  std::string index;  // out_dir/index.html
  std::size_t runs = 0, series = 0, hosts = 0;
  std::vector<ReportedStep> steps;  // by run order, then series
};

// Writes the site into out_dir (created; files written whole). Throws
// InputError for unknown quantities and std::runtime_error when matplotlib
// is missing (saying what to install), as `shadowbench report` does.
HistoryReport write_history_report(const HistoryDb& db, const std::string& out_dir,
                                   const HistoryReportOptions& options = {});

}  // namespace sb::history
