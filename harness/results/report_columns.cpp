#include "results/report_columns.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <stdexcept>

#include "core/format_number.h"
#include "record/figures.h"
#include "reference/reference.h"
#include "results/noisy_jobs.h"

namespace sb::results {

using core::format_number;
using record::ImageMetrics;
using record::JobRecord;
using record::JobStatus;
using record::ReferenceRecord;
using record::RegionStats;
using record::Series;
using record::to_string;

namespace {

// The image a column's figure is of: the visibility against the reference,
// or against the second reference (null where the record has none).
using ImageOf = const ImageMetrics* (*)(const JobRecord&);

const ImageMetrics* visibility(const JobRecord& r) {
  return r.metrics ? &r.metrics->visibility : nullptr;
}

const ImageMetrics* second_visibility(const JobRecord& r) {
  return r.second_reference ? &r.second_reference->visibility : nullptr;
}

// The GPU memory the technique reports (technique.gpu_bytes): its own and its
// needs', in MiB; none for older records, which counted its own only.
std::optional<double> gpu_mib(const JobRecord& r) {
  const auto bytes = r.technique.gpu_total_bytes();
  if (!bytes) return std::nullopt;
  return double(*bytes) / (1024.0 * 1024.0);
}

bool is_exact(const ReferenceRecord& r) { return r.method == reference::kExactMethod; }

// Of the penumbra MSE against the Monte Carlo reference, the share its noise
// explains: (MSE_mc - MSE_exact) / MSE_mc, when one reference is exact and the
// other Monte Carlo, over the same pixels.
std::optional<double> mc_noise_share(const JobRecord& r) {
  if (!r.metrics || !r.reference || !r.second_reference) return std::nullopt;
  const bool first_exact = is_exact(*r.reference);
  if (first_exact == is_exact(r.second_reference->reference)) return std::nullopt;
  const double first = r.metrics->visibility.penumbra.rmse;
  const double other = r.second_reference->visibility.penumbra.rmse;
  const double exact = first_exact ? first : other, mc = first_exact ? other : first;
  if (!(mc > 0.0)) return std::nullopt;
  return (mc * mc - exact * exact) / (mc * mc);
}

// The record's lit / penumbra / umbra confusion against the reference.
std::optional<double> penumbra_missed(const JobRecord& r) {
  return r.classes ? r.classes->penumbra_missed() : std::nullopt;
}
std::optional<double> penumbra_invented(const JobRecord& r) {
  return r.classes ? r.classes->penumbra_invented() : std::nullopt;
}

// Names and labels made from the catalogue, kept as long as the columns.
const char* kept(std::string text) {
  static std::deque<std::string> texts;
  return texts.emplace_back(std::move(text)).c_str();
}

ReportColumn figure_column(const char* name, const char* label, const record::FieldInfo& info) {
  ReportColumn c;
  c.name = c.header = name;
  c.label = label;
  c.unit = info.unit;
  c.better = info.display.better;
  c.format = info.display.format;
  return c;
}

// A statistic of `image` over a region (record/figures.h): named by its key
// over the tables' default region, `geometry`, else by the region's column
// name and its key ("penumbra_rmse", "Penumbra RMSE"); absent where the
// record lacks the region.
ReportColumn statistic_column(ImageOf image, const std::string& region_key,
                              const std::string& statistic_key) {
  const record::Region& region = *record::find_region(region_key);
  const record::Statistic& statistic = *record::find_statistic(statistic_key);
  const bool tables_default = region_key == "geometry";
  ReportColumn c = figure_column(
      tables_default ? kept(statistic.key) : kept(region.column + "_" + statistic.key),
      tables_default
          ? statistic.info.display.label
          : kept(std::string(region.info.display.label) + " " + statistic.info.display.label),
      statistic.info);
  c.number = [image, &region, &statistic](const JobRecord& r) -> std::optional<double> {
    const ImageMetrics* m = image(r);
    const RegionStats* s = m != nullptr ? region.of(*m) : nullptr;
    if (s == nullptr) return std::nullopt;
    return statistic.value(*s);
  };
  return c;
}

// The same statistic against the second reference: "second_rmse",
// "RMSE (2nd ref.)".
ReportColumn second_column(const std::string& region_key, const std::string& statistic_key) {
  ReportColumn c = statistic_column(second_visibility, region_key, statistic_key);
  c.name = c.header = kept(std::string("second_") + c.name);
  c.label = kept(std::string(c.label) + " (2nd ref.)");
  return c;
}

// The median of one of the job's time series (record/figures.h).
ReportColumn time_column(const std::string& key) {
  const record::TimeSeries& t = *record::find_time_series(key);
  ReportColumn c = figure_column(t.column, t.info.display.label, t.info);
  c.number = [&t](const JobRecord& r) -> std::optional<double> {
    const Series* s = r.timing ? t.series(*r.timing) : nullptr;
    if (s == nullptr) return std::nullopt;
    return s->median;
  };
  return c;
}

// The wider of the job's judged medians' intervals, frame time and frame
// ratio, relative to the median (record timing.noise); none for older
// records.
std::optional<double> time_ci(const JobRecord& r) {
  if (!r.timing || !r.timing->noise) return std::nullopt;
  return r.timing->noise->judged_ci_rel();
}

// A figure of the shaded image as a whole (MetricsRecord's own numbers).
ReportColumn whole_image_column(const char* name, const std::string& key) {
  const record::WholeImageFigure& f = *record::find_whole_image_figure(key);
  ReportColumn c = figure_column(name, f.info.display.label, f.info);
  c.number = [&f](const JobRecord& r) -> std::optional<double> {
    if (!r.metrics) return std::nullopt;
    return f.value(*r.metrics);
  };
  return c;
}

std::vector<ReportColumn> make_columns() {
  auto text = [](const char* name, std::string (*get)(const JobRecord&), bool per_group = false) {
    ReportColumn c;
    c.name = c.header = c.label = name;
    c.per_group = per_group;
    c.text = get;
    return c;
  };
  // Figures no record member holds: lower is better unless said otherwise.
  auto number = [](const char* name, std::optional<double> (*get)(const JobRecord&),
                   const char* format, const char* label, const char* unit = "",
                   Better better = Better::Lower) {
    ReportColumn c;
    c.name = c.header = name;
    c.number = get;
    c.format = format;
    c.label = label;
    c.unit = unit;
    c.better = better;
    return c;
  };
  auto optional = [](ReportColumn c) {
    c.optional = true;
    return c;
  };
  auto geometry = [](const char* statistic) {
    return statistic_column(visibility, "geometry", statistic);
  };
  auto rmse_over = [](const char* region) { return statistic_column(visibility, region, "rmse"); };
  return {
      text(
          "scene", [](const JobRecord& r) { return r.scene_variant; }, true),
      text(
          "resolution", [](const JobRecord& r) { return r.resolution; }, true),
      text("technique", [](const JobRecord& r) { return r.technique_variant; }),
      text("status", [](const JobRecord& r) { return std::string(to_string(r.status)); }),
      time_column("time.frame_ms"),
      time_column("time.technique_ms"),
      time_column("time.frame_ratio"),
      optional(number("time_ci", time_ci, "%.3f", "Median CI", "", Better::Neither)),
      optional(text("noisy",
                    [](const JobRecord& r) { return std::string(is_noisy(r) ? kNoisyMark : ""); })),
      optional(number("gpu_mib", gpu_mib, "%.2f", "GPU memory", "MiB")),
      geometry("rmse"),
      geometry("mae"),
      geometry("max_error"),
      geometry("psnr"),
      geometry("ssim"),
      geometry("frac_over_0.05"),
      optional(whole_image_column("flip", "flip_shaded")),
      rmse_over("penumbra"),
      optional(rmse_over("terminator")),
      optional(rmse_over("near_third")),
      optional(rmse_over("middle_third")),
      optional(rmse_over("far_third")),
      optional(number("penumbra_missed", penumbra_missed, "%.3f", "Penumbra missed")),
      optional(number("penumbra_invented", penumbra_invented, "%.3f", "Penumbra invented")),
      optional(second_column("geometry", "rmse")),
      optional(second_column("penumbra", "rmse")),
      optional(
          number("mc_noise_share", mc_noise_share, "%.3f", "MC noise share", "", Better::Neither)),
      text("reason", [](const JobRecord& r) { return r.reason.value_or(""); }),
  };
}

}  // namespace

std::string ReportColumn::cell(const JobRecord& r) const {
  if (text != nullptr) return text(r);
  // A job that did not finish ok shows its status and reason only, whatever
  // figures its record keeps (a failed job's are under "partial").
  if (r.status != JobStatus::Ok) return "";
  const std::optional<double> v = number(r);
  if (!v || std::isnan(*v)) return "";
  if (std::isinf(*v)) return *v > 0 ? "inf" : "-inf";
  return format_number(format, *v);
}

const std::vector<ReportColumn>& report_columns() {
  static const std::vector<ReportColumn> columns = make_columns();
  return columns;
}

const ReportColumn& report_column(const std::string& name) {
  for (const auto& c : report_columns())
    if (name == c.name) return c;
  throw std::out_of_range("no report column \"" + name + "\"");
}

std::vector<const ReportColumn*> group_table_columns(const std::vector<JobRecord>& records) {
  std::vector<const ReportColumn*> out;
  for (const auto& c : report_columns()) {
    if (c.per_group) continue;
    if (c.optional && std::none_of(records.begin(), records.end(),
                                   [&](const JobRecord& r) { return !c.cell(r).empty(); }))
      continue;
    out.push_back(&c);
  }
  return out;
}

std::string reference_label(const ReferenceRecord& r) {
  std::string out =
      is_exact(r)  ? "exact (" + r.method + ")"
      : r.adaptive ? "adaptive Monte Carlo, up to " + std::to_string(r.spp) + " spp, mean " +
                         format_number("%.1f", r.adaptive->mean_spp) + ", target std error " +
                         format_number("%g", r.adaptive->target_std_error) + " (" + r.method + ")"
                   : "Monte Carlo, " + std::to_string(r.spp) + " spp (" + r.method + ")";
  if (r.adaptive && r.adaptive->unproven_stops.value_or(0) > 0)
    out += "; " + std::to_string(*r.adaptive->unproven_stops) +
           " px stopped at an agreeing pilot without proof (bias at most " +
           format_number("%.3g", r.adaptive->stop_bias_bound.value_or(0.0)) + " each)";
  if (!r.exact_fallback.empty()) out += "; not exact: " + r.exact_fallback;
  return out;
}

}  // namespace sb::results
