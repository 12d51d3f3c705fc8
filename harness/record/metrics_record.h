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

// One image over one region of pixels (as metrics::ErrorStats).
struct RegionStats {
  static constexpr RecordDoc kSchema{
      "RegionStats", "one image's error against the reference's over one region of pixels"};

  std::int64_t pixel_count = 0;
  double rmse = 0, mae = 0, max_error = 0;
  int max_x = -1, max_y = -1;  // "max_pixel": [x, y]
  double psnr = 0, ssim = 1;
  double frac_over_001 = 0, frac_over_005 = 0, frac_over_01 = 0;  // "frac_over_0.01" ...
  std::int64_t nonfinite_count = 0;
  double mean_signed = 0;
  std::optional<double> flip_mean;  // absent from records written before it existed

  template <class V>
  static void describe(V& v) {
    using R = RegionStats;
    v.field("pixel_count", &R::pixel_count, {"px", "pixels in the region"});
    v.field("rmse", &R::rmse, {"", "root mean square error"});
    v.field("mae", &R::mae, {"", "mean absolute error"});
    v.field("max_error", &R::max_error, {"", "largest absolute error"});
    v.custom(
        "max_pixel", "[integer, integer]", {"px", "[x, y] of the largest error"},
        [](const R& s) {
          return std::optional(nlohmann::json::array({s.max_x, s.max_y}));
        },
        [](R& s, const Fields& f) { read_max_pixel(s, f); });
    v.field("psnr", &R::psnr, {"dB", "peak signal-to-noise ratio"});
    v.field("ssim", &R::ssim, {"", "structural similarity"});
    v.field("frac_over_0.01", &R::frac_over_001, {"", "share of pixels with error over 0.01"});
    v.field("frac_over_0.05", &R::frac_over_005, {"", "share of pixels with error over 0.05"});
    v.field("frac_over_0.1", &R::frac_over_01, {"", "share of pixels with error over 0.1"});
    v.field("nonfinite_count", &R::nonfinite_count, {"px", "NaN or infinite pixels"});
    v.field("mean_signed", &R::mean_signed, {"", "mean of technique − reference"});
    v.field("flip_mean", &R::flip_mean,
            {"",
             "mean LDR-FLIP (Andersson et al. 2020, metrics/flip.h) over the region, its map "
             "computed as the region's SSIM is (\"Regions\" above), at "
             "`metrics.flip_pixels_per_degree`: V as a grey image; the shaded image decoded "
             "from sRGB, as FLIP's own tool reads shaded.png; absent from older records"});
  }
  static void read_max_pixel(RegionStats& s, const Fields& f);

  nlohmann::json to_json() const;
  static RegionStats from_json(const Fields& f);
};

// The regions (docs/results.md, "Regions"): all measured pixels, sky and
// attached shadow included (kept for older records and tools); `geometry`,
// the measured surface pixels outside attached shadow, the error that does
// not depend on framing (absent from records written before it existed);
// the reference's penumbra, the soft pixels of either image, and the
// measured pixels on meshes that cast no shadow (a ground: where the seed
// papers compare shadows; absent when the image has none, and in records
// written before it existed). `terminator`: the pixels whose tangent plane
// cuts the light, which no other region holds (absent from records written
// before it existed). With the
// config's metrics.distance_thirds, the visibility's measured pixels also
// by distance from the camera (metrics/distance_thirds.h): near_third,
// middle_third, far_third.
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
    v.field("all", &M::all, {"", "all measured pixels, sky and attached shadow included"});
    v.field("geometry", &M::geometry,
            {"",
             "the measured surface pixels outside attached shadow; absent from records "
             "written before it existed"});
    v.field("penumbra", &M::penumbra, {"", "the reference's penumbra"});
    v.field("soft_union", &M::soft_union, {"", "the soft pixels of either image"});
    v.field("receivers", &M::receivers,
            {"", "the measured pixels on meshes that cast no shadow; absent when there are none"});
    v.field("terminator", &M::terminator,
            {"",
             "the pixels whose tangent plane cuts the light (`reference.horizon_cut_pixels`), in "
             "no other region, measured on their own; figures NaN when there are none; absent "
             "from records written before it existed"});
    v.field("near_third", &M::near_third,
            {"", "with `metrics.distance_thirds`: the nearest third of the measured pixels"});
    v.field("middle_third", &M::middle_third, {"", "with `metrics.distance_thirds`"});
    v.field("far_third", &M::far_third, {"", "with `metrics.distance_thirds`"});
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
    v.field("visibility", &MetricsRecord::visibility, {"", "the visibility buffer V"});
    v.field("shaded", &MetricsRecord::shaded,
            {"", "the image shaded from the same V, after the attached-shadow rule"});
    v.field("flip_shaded", &MetricsRecord::flip_shaded,
            {"",
             "mean LDR-FLIP of shaded.png against the reference's shaded.png over every pixel, "
             "nothing replaced, at `metrics.flip_pixels_per_degree`: what NVIDIA's `flip` tool "
             "prints for the two files, the map `images.flip_shaded` shows and the report's "
             "`flip` column; absent from older records"});
  }

  nlohmann::json to_json() const;
  static MetricsRecord from_json(const Fields& f);
};

// A metric named by its dotted path under "metrics":
// <visibility|shaded>.<geometry|all|penumbra|soft_union|receivers|
// terminator|near_third|middle_third|far_third>.<key>, e.g.
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
  bool holds(const MetricsRecord& m) const { return region_(m.*image_) != nullptr; }
  const std::string& key() const { return key_; }  // "rmse", "frac_over_0.05", ...

 private:
  ImageMetrics MetricsRecord::*image_ = nullptr;
  const RegionStats* (*region_)(const ImageMetrics&) = nullptr;
  std::string key_;
};

}  // namespace sb::record
