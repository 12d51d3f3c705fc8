#include "history/run_points.h"

#include <algorithm>
#include <cmath>

#include "record/figures.h"
#include "record/timing_stats.h"

namespace sb::history {

using record::JobRecord;
using record::JobStatus;

namespace {

// Every finite number of the catalogue (record/figures.h) that the record's
// metrics hold, by its dotted path below "metrics", in the order of the
// paths (as the record's JSON has them).
void add_metrics(const record::MetricsRecord& m, std::vector<std::pair<std::string, double>>& out) {
  std::vector<std::pair<std::string, double>> all;
  for (const record::WholeImageFigure& f : record::whole_image_figures())
    if (const std::optional<double> v = f.value(m)) all.emplace_back("metrics." + f.key, *v);
  for (const record::Image& image : record::images())
    for (const record::Region& region : record::regions())
      if (const record::RegionStats* s = region.of(m.*image.member))
        for (const record::Statistic& statistic : record::statistics())
          all.emplace_back("metrics." + image.key + "." + region.key + "." + statistic.key,
                           statistic.value(*s));
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [path, value] : all)
    if (std::isfinite(value)) out.emplace_back(path, value);
}

// A job's own noise of a median: the 95 % interval of the median of its
// frames (record/median_interval.h, as the record's median_ci_rel, here
// from the samples, so that records from before that field have it too),
// half its width over the median, / 1.96: the standard error it implies.
// NaN below 6 frames, where no interval reaches 95 %.
double own_noise(const std::vector<double>& samples) {
  const record::TimingStats stats = record::summarize(samples);
  if (stats.count < 6 || !(stats.median > 0) || stats.median_ci_coverage < 0.95)
    return std::nan("");
  constexpr double kZ95 = 1.959963984540054;
  return stats.median_ci_rel() / kZ95;
}

void add_if_finite(const std::string& quantity, double v,
                   std::vector<std::pair<std::string, double>>& out) {
  if (std::isfinite(v)) out.emplace_back(quantity, v);
}

}  // namespace

std::string series_name(const std::string& scene_variant, const std::string& resolution,
                        const std::string& technique_variant) {
  return scene_variant + " @ " + resolution + " / " + technique_variant;
}

std::vector<JobPoints> run_points(const std::vector<JobRecord>& records) {
  std::vector<JobPoints> out;
  out.reserve(records.size());
  for (const JobRecord& r : records) {
    JobPoints p;
    p.job_id = r.job_id;
    p.scene_variant = r.scene_variant;
    p.resolution = r.resolution;
    p.technique_variant = r.technique_variant;
    p.series = series_name(r.scene_variant, r.resolution, r.technique_variant);
    p.status = record::to_string(r.status);
    p.reason = r.reason.value_or("");
    p.host_fingerprint = r.host.fingerprint.value_or("");
    p.build_fingerprint = r.build.fingerprint.value_or("");
    if (r.status == JobStatus::Ok && r.timing)
      for (const record::TimeSeries& t : record::time_series())
        if (const record::Series* s = t.series(*r.timing); s != nullptr && s->count > 0) {
          add_if_finite(t.key, s->median, p.values);
          if (const double e = own_noise(s->samples); std::isfinite(e)) p.noise[t.key] = e;
        }
    if (r.status == JobStatus::Ok && r.metrics) add_metrics(*r.metrics, p.values);
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace sb::history
