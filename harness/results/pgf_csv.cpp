#include "results/pgf_csv.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/format_number.h"
#include "record/figures.h"
#include "results/latex_tables.h"
#include "results/pareto.h"

namespace sb::results {

using core::format_number;
using core::InputError;
using record::JobRecord;
using record::JobStatus;
using record::MetricPath;

namespace {

struct PgfRow {
  const JobRecord* record = nullptr;
  double time = 0.0, error = 0.0;
};

std::string pgf_number(double v) { return std::isfinite(v) ? format_number("%.6g", v) : "nan"; }

}  // namespace

std::string make_error_time_csv(const std::vector<const JobRecord*>& group,
                                const std::string& error_metric) {
  const std::optional<MetricPath> path = MetricPath::parse(error_metric);
  if (!path) throw InputError("", "--metric", "unknown error metric \"" + error_metric + "\"");
  const bool higher = path->statistic().info.display.better == record::Better::Higher;
  std::vector<PgfRow> rows;
  for (const JobRecord* r : group) {
    if (r->status != JobStatus::Ok || !r->timing) continue;
    const double time = r->timing->frame.median;
    const double error = r->metric(*path).value_or(std::nan(""));
    if (std::isfinite(time) && std::isfinite(error)) rows.push_back({r, time, error});
  }
  std::stable_sort(rows.begin(), rows.end(),
                   [](const PgfRow& a, const PgfRow& b) { return a.time < b.time; });
  std::vector<ParetoPoint> points;
  points.reserve(rows.size());
  for (const PgfRow& row : rows)
    points.push_back({row.time, higher ? -row.error : row.error, row.record->technique_variant});
  std::vector<bool> on_front(rows.size(), false);
  for (const size_t i : pareto_front_indices(points)) on_front[i] = true;

  std::string out = "technique,time_ms,time_p10_ms,time_p90_ms,error,pareto\n";
  for (size_t i = 0; i < rows.size(); ++i) {
    const record::Series& frame = rows[i].record->timing->frame;
    out += "{" + latex_text(rows[i].record->technique_variant) + "}," + pgf_number(rows[i].time) +
           "," + pgf_number(frame.p10) + "," + pgf_number(frame.p90) + "," +
           pgf_number(rows[i].error) + "," + (on_front[i] ? "1" : "0") + "\n";
  }
  return out;
}

}  // namespace sb::results
