#include "results/pgf_csv.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/format_number.h"
#include "record/figures.h"
#include "results/control_baseline.h"
#include "results/latex_tables.h"
#include "results/pareto.h"

namespace sb::results {

using core::format_number;
using core::InputError;
using record::JobRecord;
using record::JobStatus;
using record::MetricPath;

namespace {

std::string pgf_number(double v) { return std::isfinite(v) ? format_number("%.6g", v) : "nan"; }

}  // namespace

std::vector<ErrorTimeRow> error_time_rows(const std::vector<const JobRecord*>& group,
                                          const std::string& error_metric) {
  const std::optional<MetricPath> path = MetricPath::parse(error_metric);
  if (!path) throw InputError("", "--metric", "unknown error metric \"" + error_metric + "\"");
  const bool higher = path->higher_is_better();
  std::vector<ErrorTimeRow> rows;
  for (const JobRecord* r : group) {
    if (r->status != JobStatus::Ok || !r->timing) continue;
    const double time = r->timing->frame.median;
    const double error = r->metric(*path).value_or(std::nan(""));
    if (std::isfinite(time) && std::isfinite(error))
      rows.push_back({r, time, error, false, is_control(group, *r)});
  }
  std::stable_sort(rows.begin(), rows.end(),
                   [](const ErrorTimeRow& a, const ErrorTimeRow& b) { return a.time < b.time; });
  // The control competes for no place on the front: its point is NaN there.
  std::vector<ParetoPoint> points;
  points.reserve(rows.size());
  for (const ErrorTimeRow& row : rows)
    points.push_back({row.control ? std::nan("") : row.time, higher ? -row.error : row.error,
                      row.record->technique_variant});
  for (const size_t i : pareto_front_indices(points)) rows[i].pareto = true;
  return rows;
}

std::string make_error_time_csv(const std::vector<const JobRecord*>& group,
                                const std::string& error_metric) {
  std::string out = "technique,time_ms,time_p10_ms,time_p90_ms,error,pareto,control\n";
  for (const ErrorTimeRow& row : error_time_rows(group, error_metric)) {
    const record::Series& frame = row.record->timing->frame;
    out += "{" + latex_text(row.record->technique_variant) + "}," + pgf_number(row.time) + "," +
           pgf_number(frame.p10) + "," + pgf_number(frame.p90) + "," + pgf_number(row.error) + "," +
           (row.pareto ? "1" : "0") + "," + (row.control ? "1" : "0") + "\n";
  }
  return out;
}

}  // namespace sb::results
