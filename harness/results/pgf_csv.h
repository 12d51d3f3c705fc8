#pragma once
// The error-against-frame-time data of one (scene variant, resolution), as
// the error_time chart draws them (results/charts.h), in a CSV that
// pgfplots reads with \addplot table[x=time_ms, y=error, col sep=comma]
// (`report --latex`, docs/paper.md):
//
//   technique,time_ms,time_p10_ms,time_p90_ms,error,pareto,control
//   {pcf\_box/k=3,size=1024},9.01,8.95,9.2,0.0123,1,0
//
// One row per ok job with a finite frame time and error, by time. The
// technique is LaTeX text (latex_text) in braces, pgfplots' grouping, so a
// comma in a name stays in its cell and the name typesets as itself
// (meta=technique with point meta=explicit symbolic). error is the chart's
// metric (--metric); pareto is 1 on the chart's Pareto front (higher is
// better for psnr and ssim), else 0; control is 1 on the timing control's
// row (results/control_baseline.h), which is never on the front. Numbers are
// printed with %.6g.
#include <string>
#include <vector>

#include "record/job_record.h"

namespace sb::results {

// One row of the CSV: its record, frame time (median, ms) and error.
struct ErrorTimeRow {
  const record::JobRecord* record = nullptr;
  double time = 0, error = 0;
  bool pareto = false;   // on the front
  bool control = false;  // the timing control
};

// The rows, by time. Throws InputError at "--metric" for a metric path that
// names no number.
std::vector<ErrorTimeRow> error_time_rows(const std::vector<const record::JobRecord*>& group,
                                          const std::string& error_metric);

// The CSV of error_time_rows(); throws as it does.
std::string make_error_time_csv(const std::vector<const record::JobRecord*>& group,
                                const std::string& error_metric);

}  // namespace sb::results
