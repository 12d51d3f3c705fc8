#pragma once
// record["metrics"]: the error of a technique's visibility buffer and shaded
// image against the reference's, per region (docs/results.md, "metrics").
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "record/describe.h"
#include "record/fields.h"

namespace sb::record {

// One image over one region of pixels: the per-region statistics, each
// described once here (key, unit, doc and how reports show it) for the JSON,
// the schema tables, metric paths, report columns and charts alike
// (record/figures.h). metrics::compare() computes it (metrics::ErrorStats).
struct RegionStats {
  static constexpr RecordDoc kSchema{
      "RegionStats", "one image's error against the reference's over one region of pixels"};

  // Pixels included (mask applied).
  std::int64_t pixel_count = 0;
  // Over all channels of the included pixels, as OIIO's compare():
  // mae = sum|d| / (n*channels), rmse = sqrt(sum d^2 / (n*channels)),
  // d = |float(test - ref)| accumulated in double.
  double rmse = 0, mae = 0, max_error = 0;
  // First (row-major, then channel) value with the largest error; -1 when no
  // included value differs at all (OIIO reports 0,0,0 there). "max_pixel":
  // [x, y]; the channel is not recorded.
  int max_x = -1, max_y = -1, max_channel = -1;
  // 20*log10(1/rmse) (data range 1); +inf when rmse == 0. Equal to OIIO's
  // PSNR while no value exceeds 1 in magnitude (OIIO then uses the largest
  // absolute value as the peak instead of 1).
  double psnr = 0;
  // Mean SSIM (metrics::ssim()); NaN when the image is smaller than the
  // 11x11 window or no included pixel lies in the evaluated region.
  double ssim = 1;
  // Share of included PIXELS whose error (max over channels) is > 0.01/0.05/0.1.
  double frac_over_001 = 0, frac_over_005 = 0, frac_over_01 = 0;  // "frac_over_0.01" ...
  // Included values where test and ref are not both finite and equal in kind
  // (NaN vs number, inf vs number, +inf vs -inf). Such a value counts as an
  // infinite error for max_error and the fractions but is left out of the
  // rmse/mae sums (which keep their n*channels divisor), so one stray NaN
  // does not turn every figure into NaN. NaN==NaN and inf==inf (same sign)
  // count as exact matches.
  std::int64_t nonfinite_count = 0;
  // mean(test - ref) over the same values: its sign tells over-darkening
  // (negative for visibility) from leaking light (positive).
  double mean_signed = 0;
  std::optional<double> flip_mean;  // absent from records written before it existed

  template <class V>
  static void describe(V& v) {
    using R = RegionStats;
    constexpr Better lower = Better::Lower, higher = Better::Higher, neither = Better::Neither;
    v.field("pixel_count", &R::pixel_count,
            {.unit = "px", .doc = "pixels in the region", .display = {"Pixels", neither, "%.0f"}});
    v.field("rmse", &R::rmse,
            {.doc = "root mean square error", .display = {"RMSE", lower, "%.5f"}});
    v.field("mae", &R::mae, {.doc = "mean absolute error", .display = {"MAE", lower, "%.5f"}});
    v.field("max_error", &R::max_error,
            {.doc = "largest absolute error", .display = {"Max error", lower, "%.4f"}});
    v.custom(
        "max_pixel", "[integer, integer]", {"px", "[x, y] of the largest error"},
        [](const R& s) {
          return std::optional(nlohmann::json::array({s.max_x, s.max_y}));
        },
        [](R& s, const Fields& f) { read_max_pixel(s, f); });
    v.field(
        "psnr", &R::psnr,
        {.unit = "dB", .doc = "peak signal-to-noise ratio", .display = {"PSNR", higher, "%.2f"}});
    v.field("ssim", &R::ssim,
            {.doc = "structural similarity", .display = {"SSIM", higher, "%.4f"}});
    v.field("frac_over_0.01", &R::frac_over_001,
            {.doc = "share of pixels with error over 0.01",
             .display = {"Error > 0.01", lower, "%.4f"}});
    v.field("frac_over_0.05", &R::frac_over_005,
            {.doc = "share of pixels with error over 0.05",
             .display = {"Error > 0.05", lower, "%.4f"}});
    v.field(
        "frac_over_0.1", &R::frac_over_01,
        {.doc = "share of pixels with error over 0.1", .display = {"Error > 0.1", lower, "%.4f"}});
    v.field(
        "nonfinite_count", &R::nonfinite_count,
        {.unit = "px", .doc = "NaN or infinite pixels", .display = {"Non-finite", lower, "%.0f"}});
    v.field("mean_signed", &R::mean_signed,
            {.doc = "mean of technique − reference",
             .display = {"Mean signed error", neither, "%.5f"}});
    v.field("flip_mean", &R::flip_mean,
            {.doc = "mean LDR-FLIP (Andersson et al. 2020, metrics/flip.h) over the region, its "
                    "map computed as the region's SSIM is (\"Regions\" above), at "
                    "`metrics.flip_pixels_per_degree`: V as a grey image; the shaded image "
                    "decoded from sRGB, as FLIP's own tool reads shaded.png; absent from older "
                    "records",
             .display = {"FLIP", lower, "%.4f"}});
  }
  static void read_max_pixel(RegionStats& s, const Fields& f);

  nlohmann::json to_json() const;
  static RegionStats from_json(const Fields& f);
};

// The regions (docs/results.md, "Regions"), each described once here: its
// record key, what it holds and its name in reports (record/figures.h lists
// them in this order; metrics/region_masks.h makes each one's pixels). All
// measured pixels, sky and attached shadow included (kept for older records
// and tools); `geometry`, the measured surface pixels outside attached
// shadow, the error that does not depend on framing; the reference's
// penumbra, the soft pixels of either image, and the measured pixels on
// meshes that cast no shadow (a ground: where the seed papers compare
// shadows). `terminator`: the pixels whose tangent plane cuts the light,
// which no other region holds. With the config's metrics.distance_thirds,
// the visibility's measured pixels also by distance from the camera
// (metrics/distance_thirds.h).
struct ImageMetrics {
  static constexpr RecordDoc kSchema{"ImageMetrics",
                                     "one image's errors, per region (\"Regions\" above)"};

  RegionStats all, penumbra, soft_union;
  std::optional<RegionStats> geometry = std::nullopt;
  std::optional<RegionStats> receivers = std::nullopt;
  std::optional<RegionStats> terminator = std::nullopt;
  std::optional<RegionStats> near_third = std::nullopt;
  std::optional<RegionStats> middle_third = std::nullopt;
  std::optional<RegionStats> far_third = std::nullopt;

  template <class V>
  static void describe(V& v) {
    using M = ImageMetrics;
    v.field("all", &M::all,
            {.doc = "all measured pixels, sky and attached shadow included",
             .display = {.label = "All"}});
    v.field("geometry", &M::geometry,
            {.doc = "the measured surface pixels outside attached shadow; absent from records "
                    "written before it existed",
             .display = {.label = "Geometry"}});
    v.field("penumbra", &M::penumbra,
            {.doc = "the reference's penumbra", .display = {.label = "Penumbra"}});
    v.field("soft_union", &M::soft_union,
            {.doc = "the soft pixels of either image", .display = {.label = "Soft union"}});
    v.field("receivers", &M::receivers,
            {.doc = "the measured pixels on meshes that cast no shadow; absent when there are "
                    "none",
             .display = {.label = "Receivers"}});
    v.field("terminator", &M::terminator,
            {.doc = "the pixels whose tangent plane cuts the light "
                    "(`reference.horizon_cut_pixels`), in no other region, measured on their "
                    "own; figures NaN when there are none; absent from records written before "
                    "it existed",
             .display = {.label = "Terminator"}});
    v.field("near_third", &M::near_third,
            {.doc = "with `metrics.distance_thirds`: the measured pixels in the nearest third of "
                    "their distances' range from the camera (equal thirds of distance, or of its "
                    "logarithm with `metrics.distance_scale` \"log\")",
             .display = {.label = "Near"}});
    v.field("middle_third", &M::middle_third,
            {.doc = "with `metrics.distance_thirds`", .display = {.label = "Middle"}});
    v.field("far_third", &M::far_third,
            {.doc = "with `metrics.distance_thirds`", .display = {.label = "Far"}});
  }

  nlohmann::json to_json() const;
  static ImageMetrics from_json(const Fields& f);
};

struct MetricsRecord {
  static constexpr RecordDoc kSchema{"MetricsRecord",
                                     "the error of the technique's images against the reference's"};

  ImageMetrics visibility, shaded;
  // FLIP as papers print it: of shaded.png against the reference's, every
  // pixel, nothing replaced (absent from records written before it).
  std::optional<double> flip_shaded = std::nullopt;

  template <class V>
  static void describe(V& v) {
    v.field("visibility", &MetricsRecord::visibility,
            {.doc = "the visibility buffer V", .display = {.label = "Visibility"}});
    v.field("shaded", &MetricsRecord::shaded,
            {.doc = "the image shaded from the same V, after the attached-shadow rule",
             .display = {.label = "Shaded"}});
    v.field("flip_shaded", &MetricsRecord::flip_shaded,
            {.doc = "mean LDR-FLIP of shaded.png against the reference's shaded.png over every "
                    "pixel, nothing replaced, at `metrics.flip_pixels_per_degree`: what "
                    "NVIDIA's `flip` tool prints for the two files, the map "
                    "`images.flip_shaded` shows and the report's `flip` column; absent from "
                    "older records",
             .display = {"FLIP", Better::Lower, "%.4f"}});
  }

  nlohmann::json to_json() const;
  static MetricsRecord from_json(const Fields& f);
};

struct Image;
struct Region;
struct Statistic;

// A metric named by its dotted path under "metrics": <image>.<region>.<key>
// of the catalogue (record/figures.h; metric_path_syntax() spells it), e.g.
// visibility.geometry.rmse or visibility.all.frac_over_0.05 (a key may hold
// dots). A region the record lacks (geometry and terminator in older
// records, receivers, the thirds) reads as NaN.
class MetricPath {
 public:
  // nullopt when `dotted` names no number of the schema.
  static std::optional<MetricPath> parse(const std::string& dotted);
  // NaN when the record has no such region (a region added after it was
  // written, or one its job did not measure): holds() tells the two apart.
  double of(const MetricsRecord& m) const;
  bool holds(const MetricsRecord& m) const;
  const std::string& key() const;  // "rmse", "frac_over_0.05", ...
  const Statistic& statistic() const { return *statistic_; }
  // Whether a larger value is better (the catalogue's display.better).
  bool higher_is_better() const;

 private:
  const Image* image_ = nullptr;
  const Region* region_ = nullptr;
  const Statistic* statistic_ = nullptr;
};

}  // namespace sb::record
