#include "metrics/job_metrics.h"

#include <cmath>
#include <vector>

#include "metrics/flip.h"
#include "metrics/geometry_region.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"

namespace sb::metrics {

using core::ImageF;
using record::ImageMetrics;
using record::MetricsRecord;
using record::RegionStats;
using record::VisibilityCheckRecord;

namespace {

RegionStats region_stats(const ErrorStats& s) {
  RegionStats r;
  r.pixel_count = static_cast<std::int64_t>(s.pixel_count);
  r.rmse = s.rmse;
  r.mae = s.mae;
  r.max_error = s.max_error;
  r.max_x = s.max_x;
  r.max_y = s.max_y;
  r.psnr = s.psnr;
  r.ssim = s.ssim;
  r.frac_over_001 = s.frac_over_001;
  r.frac_over_005 = s.frac_over_005;
  r.frac_over_01 = s.frac_over_01;
  r.nonfinite_count = static_cast<std::int64_t>(s.nonfinite_count);
  r.mean_signed = s.mean_signed;
  return r;
}

// A region with no pixel: every figure undefined, as compare() gives it.
RegionStats no_pixels() {
  ErrorStats s;
  s.rmse = s.mae = s.max_error = s.psnr = s.ssim = s.mean_signed = std::nan("");
  s.frac_over_001 = s.frac_over_005 = s.frac_over_01 = std::nan("");
  return region_stats(s);
}

// Regions, each only over the measured pixels (all but those whose tangent
// plane cuts the light; see metrics/light_horizon.h): every pixel; the
// reference's penumbra; the soft pixels of either the technique or the
// reference (`soft_union`), which also sees light bleeding into a true umbra
// and blur outside the true penumbra; and, when the view holds any, the
// pixels on meshes that cast no shadow (`receivers`). `geometry`, the surface
// outside attached shadow, is measured on its own (metrics/geometry_region.h):
// its SSIM windows see the reference's values everywhere outside it. So is
// `terminator`, the pixels whose tangent plane cuts the light, which no other
// region holds: the technique's own values there, the reference's outside.
//
// SSIM's windows reach past the mask, so the unmeasured pixels take the
// reference's values first: they add no error to a neighbour either.
//
// `extra` masks are measured too, in the same pass of the SSIM window (the
// window's cost does not depend on how many masks average it); their stats
// come back in order.
ImageMetrics compare_images(const ImageF& test, const ImageF& ref, const Regions& regions,
                            const std::vector<uint8_t>& soft_union,
                            const std::vector<const std::vector<uint8_t>*>& extra = {},
                            std::vector<RegionStats>* extra_stats = nullptr) {
  const ImageF t = with_unmeasured_from(test, ref, regions.measured);
  std::vector<const std::vector<uint8_t>*> masks = {&regions.measured, &regions.penumbra,
                                                    &soft_union};
  if (regions.any_receiver) masks.push_back(&regions.receivers);
  // Geometry shares the SSIM pass unless the technique wrote something other
  // than the reference outside it (on the sky, say): then it needs its own.
  const bool geometry_shares = matches_outside(t, ref, regions.geometry);
  if (geometry_shares) masks.push_back(&regions.geometry);
  const size_t first_extra = masks.size();
  masks.insert(masks.end(), extra.begin(), extra.end());
  const std::vector<ErrorStats> stats = compare(t, ref, masks);
  ImageMetrics m{region_stats(stats[0]), region_stats(stats[1]), region_stats(stats[2])};
  m.geometry = region_stats(geometry_shares ? stats[first_extra - 1]
                                            : compare_within(t, ref, regions.geometry));
  if (regions.any_receiver) m.receivers = region_stats(stats[3]);
  m.terminator = count_ones(regions.terminator) == 0
                     ? no_pixels()
                     : region_stats(compare_within(test, ref, regions.terminator));
  if (extra_stats != nullptr)
    for (size_t i = first_extra; i < stats.size(); ++i)
      extra_stats->push_back(region_stats(stats[i]));
  return m;
}

// The mean of a one-channel map over a mask (NaN over no pixel).
double masked_mean(const ImageF& map, const std::vector<uint8_t>& mask) {
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t p = 0; p < mask.size(); ++p)
    if (mask[p]) sum += map.data[p], ++n;
  return n == 0 ? std::nan("") : sum / static_cast<double>(n);
}

// The FLIP map of test against ref with every pixel outside `inside` taking
// ref's values, as compare_within does for SSIM.
ImageF flip_within(const ImageF& test, const ImageF& ref, const std::vector<uint8_t>& inside,
                   double pixels_per_degree) {
  return flip(ref, with_unmeasured_from(test, ref, inside), pixels_per_degree).error;
}

// Each region's mean of the FLIP map of test against ref, the map computed
// as the region's SSIM is (compare_images): with the unmeasured pixels from
// ref, and for `geometry` and `terminator` with every pixel outside the
// region from ref. Geometry shares the first map when the technique's values
// outside it already equal the reference's (every shaded image, say);
// terminator, the measured pixels being outside it, takes a map of its own
// when it has pixels.
void add_flip_means(ImageMetrics& m, const ImageF& test, const ImageF& ref, const Regions& regions,
                    const std::vector<uint8_t>& soft_union, double pixels_per_degree) {
  const ImageF t = with_unmeasured_from(test, ref, regions.measured);
  const ImageF map = flip(ref, t, pixels_per_degree).error;
  m.all.flip_mean = masked_mean(map, regions.measured);
  m.penumbra.flip_mean = masked_mean(map, regions.penumbra);
  m.soft_union.flip_mean = masked_mean(map, soft_union);
  if (m.geometry)
    m.geometry->flip_mean =
        masked_mean(matches_outside(t, ref, regions.geometry)
                        ? map
                        : flip_within(t, ref, regions.geometry, pixels_per_degree),
                    regions.geometry);
  if (m.receivers) m.receivers->flip_mean = masked_mean(map, regions.receivers);
  if (m.terminator && m.terminator->pixel_count > 0)
    m.terminator->flip_mean = masked_mean(
        flip_within(test, ref, regions.terminator, pixels_per_degree), regions.terminator);
  if (regions.distance_thirds) {
    std::optional<RegionStats>* thirds[] = {&m.near_third, &m.middle_third, &m.far_third};
    for (std::size_t i = 0; i < 3; ++i)
      if (*thirds[i]) (*thirds[i])->flip_mean = masked_mean(map, (*regions.distance_thirds)[i]);
  }
}

// The image as shaded.png holds it (8 bits a value), decoded from sRGB: what
// FLIP's own tool reads from the file, so that the figure can be recomputed
// from it.
ImageF as_flip_reads_png(const ImageF& shaded) {
  ImageF q = shaded;
  for (float& v : q.data) v = static_cast<float>(io::png_byte(v)) / 255.0f;
  return linear_from_srgb(q);
}

}  // namespace

VisibilityKind visibility_kind(float v) {
  if (!std::isfinite(v)) return VisibilityKind::Nonfinite;
  if (v < -kVisibilityTolerance) return VisibilityKind::Below0;
  if (v > 1.0f + kVisibilityTolerance) return VisibilityKind::Above1;
  return VisibilityKind::Valid;
}

VisibilityCheckRecord check_visibility(const ImageF& visibility) {
  VisibilityCheckRecord c;
  c.tolerance = kVisibilityTolerance;
  for (float x : visibility.data) {
    switch (visibility_kind(x)) {
      case VisibilityKind::Nonfinite:
        ++c.nonfinite;
        break;
      case VisibilityKind::Below0:
        ++c.below_0;
        break;
      case VisibilityKind::Above1:
        ++c.above_1;
        break;
      case VisibilityKind::Valid:
        break;
    }
  }
  return c;
}

ImageF invalid_visibility_image(const ImageF& visibility) {
  ImageF out(visibility.width, visibility.height, 3);
  for (std::size_t p = 0; p < visibility.pixel_count(); ++p) {
    float* rgb = &out.data[p * 3];
    switch (visibility_kind(visibility.data[p])) {
      case VisibilityKind::Nonfinite:
        rgb[0] = 1.0f;
        break;
      case VisibilityKind::Below0:
        rgb[2] = 1.0f;
        break;
      case VisibilityKind::Above1:
        rgb[0] = rgb[1] = 1.0f;
        break;
      case VisibilityKind::Valid:
        break;
    }
  }
  return out;
}

MetricsRecord measure(const ImageF& visibility, const ImageF& shaded, const ImageF& ref_visibility,
                      const ImageF& ref_shaded, const Regions& regions,
                      double flip_pixels_per_degree, ImageF* flip_map) {
  const std::vector<uint8_t> soft_union = soft_union_of(visibility, regions);
  std::vector<const std::vector<uint8_t>*> thirds;
  if (regions.distance_thirds)
    for (const auto& third : *regions.distance_thirds) thirds.push_back(&third);
  std::vector<RegionStats> third_stats;
  MetricsRecord m{
      compare_images(visibility, ref_visibility, regions, soft_union, thirds, &third_stats),
      compare_images(shaded, ref_shaded, regions, soft_union)};
  if (regions.distance_thirds) {
    m.visibility.near_third = third_stats[0];
    m.visibility.middle_third = third_stats[1];
    m.visibility.far_third = third_stats[2];
  }
  add_flip_means(m.visibility, visibility, ref_visibility, regions, soft_union,
                 flip_pixels_per_degree);
  const ImageF shaded_png = as_flip_reads_png(shaded), ref_png = as_flip_reads_png(ref_shaded);
  add_flip_means(m.shaded, shaded_png, ref_png, regions, soft_union, flip_pixels_per_degree);
  // As FLIP's tool compares the two PNGs: every pixel, nothing replaced.
  FlipResult whole = flip(ref_png, shaded_png, flip_pixels_per_degree);
  m.flip_shaded = whole.mean;
  if (flip_map != nullptr) *flip_map = std::move(whole.error);
  return m;
}

ImageMetrics measure_visibility(const ImageF& visibility, const ImageF& ref_visibility,
                                const Regions& regions, double flip_pixels_per_degree) {
  const std::vector<uint8_t> soft_union = soft_union_of(visibility, regions);
  ImageMetrics m = compare_images(visibility, ref_visibility, regions, soft_union);
  add_flip_means(m, visibility, ref_visibility, regions, soft_union, flip_pixels_per_degree);
  return m;
}

std::optional<std::string> noise_warning(const MetricsRecord& m, double penumbra_rms_std_error) {
  const double pen_rmse =
      std::isfinite(m.visibility.penumbra.rmse) ? m.visibility.penumbra.rmse : 0.0;
  // RMS against RMS: the noise's sqrt(mean σ²), not its mean σ.
  if (penumbra_rms_std_error > 0.0 && pen_rmse > 0.0 && penumbra_rms_std_error > 0.5 * pen_rmse)
    return "reference noise (penumbra RMS std error " + std::to_string(penumbra_rms_std_error) +
           ") is over half the penumbra RMSE; raise reference.spp";
  return std::nullopt;
}

}  // namespace sb::metrics
