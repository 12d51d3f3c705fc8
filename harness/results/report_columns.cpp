#include "results/report_columns.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/format_number.h"
#include "reference/reference.h"

namespace sb::results {

using core::format_number;
using record::ImageMetrics;
using record::JobRecord;
using record::JobStatus;
using record::ReferenceRecord;
using record::RegionStats;
using record::Series;
using record::TimingRecord;
using record::to_string;

namespace {

// A figure of the visibility buffer's metrics over one region.
template <RegionStats ImageMetrics::*Region, double RegionStats::*Value>
std::optional<double> visibility(const JobRecord& r) {
  if (!r.metrics) return std::nullopt;
  return r.metrics->visibility.*Region.*Value;
}

// A figure of the visibility buffer's metrics over the geometry region, the
// tables' default (absent from records written before it existed).
template <double RegionStats::*Value>
std::optional<double> geometry(const JobRecord& r) {
  if (!r.metrics || !r.metrics->visibility.geometry) return std::nullopt;
  return *r.metrics->visibility.geometry.*Value;
}

// FLIP of the shaded image over every pixel, as NVIDIA's tool prints it for
// shaded.png against the reference's (absent from records written before it).
std::optional<double> shaded_flip(const JobRecord& r) {
  if (!r.metrics) return std::nullopt;
  return r.metrics->flip_shaded;
}

// The visibility's RMSE over the terminator band (absent from records
// written before it; NaN, an empty cell, where the view has no such pixel).
std::optional<double> terminator_rmse(const JobRecord& r) {
  if (!r.metrics || !r.metrics->visibility.terminator) return std::nullopt;
  return r.metrics->visibility.terminator->rmse;
}

template <Series TimingRecord::*Member>
std::optional<double> median_ms(const JobRecord& r) {
  if (!r.timing) return std::nullopt;
  return (*r.timing.*Member).median;
}

// The median of the job's frame time over the control's next to it.
std::optional<double> ratio_to_control(const JobRecord& r) {
  if (!r.timing || !r.timing->control) return std::nullopt;
  return r.timing->control->frame_ratio.median;
}

// The technique's GPU memory, its own and its needs' (technique.gpu_bytes),
// in MiB; none for older records, which counted its own only.
std::optional<double> gpu_mib(const JobRecord& r) {
  const auto bytes = r.technique.gpu_total_bytes();
  if (!bytes) return std::nullopt;
  return double(*bytes) / (1024.0 * 1024.0);
}

// The visibility's figure against the second reference.
template <RegionStats ImageMetrics::*Region, double RegionStats::*Value>
std::optional<double> second(const JobRecord& r) {
  if (!r.second_reference) return std::nullopt;
  return r.second_reference->visibility.*Region.*Value;
}

// The visibility's geometry RMSE against the second reference.
std::optional<double> second_geometry_rmse(const JobRecord& r) {
  if (!r.second_reference || !r.second_reference->visibility.geometry) return std::nullopt;
  return r.second_reference->visibility.geometry->rmse;
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

// The visibility's RMSE over one distance third (absent unless the config
// asked for them).
template <std::optional<RegionStats> ImageMetrics::*Third>
std::optional<double> third_rmse(const JobRecord& r) {
  if (!r.metrics || !(r.metrics->visibility.*Third)) return std::nullopt;
  return (r.metrics->visibility.*Third)->rmse;
}

// The record's lit / penumbra / umbra confusion against the reference.
std::optional<double> penumbra_missed(const JobRecord& r) {
  return r.classes ? r.classes->penumbra_missed() : std::nullopt;
}
std::optional<double> penumbra_invented(const JobRecord& r) {
  return r.classes ? r.classes->penumbra_invented() : std::nullopt;
}

std::vector<ReportColumn> make_columns() {
  using I = ImageMetrics;
  using S = RegionStats;
  auto text = [](const char* name, std::string (*get)(const JobRecord&), bool per_group = false) {
    ReportColumn c;
    c.name = c.header = c.label = name;
    c.per_group = per_group;
    c.text = get;
    return c;
  };
  // Lower is better unless said otherwise: times, memory and errors.
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
  return {
      text(
          "scene", [](const JobRecord& r) { return r.scene_variant; }, true),
      text(
          "resolution", [](const JobRecord& r) { return r.resolution; }, true),
      text("technique", [](const JobRecord& r) { return r.technique_variant; }),
      text("status", [](const JobRecord& r) { return std::string(to_string(r.status)); }),
      number("frame_ms", median_ms<&TimingRecord::frame>, "%.3f", "Frame", "ms"),
      number("technique_ms", median_ms<&TimingRecord::technique>, "%.3f", "Technique", "ms"),
      number("x_control", ratio_to_control, "%.3f", "Frame / control"),
      optional(number("gpu_mib", gpu_mib, "%.2f", "GPU memory", "MiB")),
      number("rmse", geometry<&S::rmse>, "%.5f", "RMSE"),
      number("mae", geometry<&S::mae>, "%.5f", "MAE"),
      number("max_error", geometry<&S::max_error>, "%.4f", "Max error"),
      number("psnr", geometry<&S::psnr>, "%.2f", "PSNR", "dB", Better::Higher),
      number("ssim", geometry<&S::ssim>, "%.4f", "SSIM", "", Better::Higher),
      number("frac_over_0.05", geometry<&S::frac_over_005>, "%.4f", "Error > 0.05"),
      optional(number("flip", shaded_flip, "%.4f", "FLIP")),
      number("penumbra_rmse", visibility<&I::penumbra, &S::rmse>, "%.5f", "Penumbra RMSE"),
      optional(number("terminator_rmse", terminator_rmse, "%.5f", "Terminator RMSE")),
      optional(number("near_rmse", third_rmse<&I::near_third>, "%.5f", "Near RMSE")),
      optional(number("middle_rmse", third_rmse<&I::middle_third>, "%.5f", "Middle RMSE")),
      optional(number("far_rmse", third_rmse<&I::far_third>, "%.5f", "Far RMSE")),
      optional(number("penumbra_missed", penumbra_missed, "%.3f", "Penumbra missed")),
      optional(number("penumbra_invented", penumbra_invented, "%.3f", "Penumbra invented")),
      optional(number("second_rmse", second_geometry_rmse, "%.5f", "RMSE (2nd ref.)")),
      optional(number("second_penumbra_rmse", second<&I::penumbra, &S::rmse>, "%.5f",
                      "Penumbra RMSE (2nd ref.)")),
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
