#include "history/series_history.h"

#include <cmath>
#include <map>
#include <string_view>

#include "core/error.h"
#include "record/figures.h"
#include "record/metrics_record.h"

namespace sb::history {

using core::InputError;

namespace {

constexpr std::string_view kMetricsPrefix = "metrics.";

// "ratio (time.frame_ratio), frame_ms (time.frame_ms) or technique_ms
// (time.technique_ms)".
std::string time_quantities() {
  const auto& all = record::time_series();
  std::string out;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (i > 0) out += i + 1 == all.size() ? " or " : ", ";
    out += std::string(all[i].option) + " (" + all[i].key + ")";
  }
  return out;
}

void check_quantities(const HistoryQuantities& q) {
  if (record::find_time_series(q.time) == nullptr)
    throw InputError("", "--time",
                     "unknown time quantity \"" + q.time + "\": expected " + time_quantities());
  if (q.error.rfind(kMetricsPrefix, 0) != 0 ||
      !record::MetricPath::parse(q.error.substr(kMetricsPrefix.size())))
    throw InputError("", "--metric",
                     "unknown error metric \"" + q.error +
                         "\": expected a dotted path into a record's \"metrics\", such as "
                         "visibility.geometry.rmse or shaded.penumbra.ssim: " +
                         record::metric_path_syntax());
}

std::map<std::string, QuantitySeries> by_series(std::vector<QuantitySeries> all) {
  std::map<std::string, QuantitySeries> out;
  for (QuantitySeries& s : all) out[s.series] = std::move(s);
  return out;
}

// A relative-scale series needs values > 0; one that has a 0 (a time too
// small to measure) is segmented on the absolute scale instead.
bool all_positive(const std::vector<double>& values) {
  for (double v : values)
    if (!std::isnan(v) && v <= 0) return false;
  return true;
}

}  // namespace

std::vector<SeriesHistory> series_histories(const HistoryDb& db, const HistoryQuantities& q) {
  check_quantities(q);
  auto times = by_series(db.series(q.time));
  auto errors = by_series(db.series(q.error));
  const std::size_t runs = static_cast<std::size_t>(db.run_count());
  std::vector<SeriesHistory> out;
  for (SeriesJobs& jobs : db.series_jobs()) {
    SeriesHistory s;
    s.time.assign(runs, std::nan(""));
    s.time_noise.assign(runs, std::nan(""));
    s.error.assign(runs, std::nan(""));
    if (auto it = times.find(jobs.series); it != times.end()) {
      s.time = std::move(it->second.values);
      s.time_noise = std::move(it->second.noise);
    }
    if (auto it = errors.find(jobs.series); it != errors.end())
      s.error = std::move(it->second.values);
    ChangePointOptions time_options;
    // The runs' own noise is relative: it weighs runs on the relative scale only.
    const bool relative = all_positive(s.time);
    time_options.scale = relative ? Scale::kRelative : Scale::kAbsolute;
    SeriesSegmentation time = segment_series(
        s.time, relative ? std::span<const double>(s.time_noise) : std::span<const double>(),
        time_options);
    s.time_steps = std::move(time.steps);
    s.time_sigma = time.sigma;
    s.time_serial_correlation = time.serial_correlation;
    s.time_loaded = std::move(time.loaded);
    ChangePointOptions error_options;
    error_options.scale = Scale::kAbsolute;
    s.error_steps = find_change_points(s.error, error_options);
    s.jobs = std::move(jobs);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace sb::history
