#include "metrics/job_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "metrics/flip.h"
#include "metrics/flip_reuse.h"
#include "metrics/geometry_region.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "record/figures.h"

namespace sb::metrics {

using core::ImageF;
using record::ImageMetrics;
using record::MetricsRecord;
using record::RegionStats;
using record::VisibilityCheckRecord;

namespace {

// A region with no pixel: every figure undefined, as compare() gives it.
RegionStats no_pixels() {
  RegionStats s;
  s.rmse = s.mae = s.max_error = s.psnr = s.ssim = s.mean_signed = std::nan("");
  s.frac_over_001 = s.frac_over_005 = s.frac_over_01 = std::nan("");
  return s;
}

// One region of one job: the region and its pixels (a per-job region's made
// from the job's V).
struct JobRegion {
  const RegionMask* region;
  std::vector<uint8_t> mask;
};

// The regions one image of a job is measured over, in catalogue order:
// `visibility_only` ones when `with_visibility_only`.
std::vector<JobRegion> job_regions(const Regions& regions, const ImageF& visibility,
                                   bool with_visibility_only) {
  std::vector<JobRegion> out;
  for (const RegionMask& r : regions.masks)
    if (with_visibility_only || !r.visibility_only)
      out.push_back({&r, job_mask(r, visibility, regions)});
  return out;
}

// How one region of one image is measured (Surround): with the others, on
// its own, or not at all (no pixel).
enum class Pass : std::uint8_t { Shared, Own, Empty };

// A Surround::Reference region shares the pass of the technique's measured
// pixels `t` when it lies within them and `t` already equals the reference
// outside it (metrics/geometry_region.h); one outside them (`terminator`)
// has the reference's values in `t` and is measured on the technique's own.
Pass pass_of(const JobRegion& r, const ImageF& t, const ImageF& ref, const Regions& regions) {
  if (r.region->surround == Surround::Technique) return Pass::Shared;
  if (count_ones(r.mask) == 0) return Pass::Empty;
  return mask_within(r.mask, regions.measured) && matches_outside(t, ref, r.mask) ? Pass::Shared
                                                                                  : Pass::Own;
}

// The figures of `test` against `ref` over each region, each in its slot of
// the record (record::Region::slot).
//
// SSIM's windows reach past the mask, so the unmeasured pixels take the
// reference's values first: they add no error to a neighbour either. Every
// region sharing that image is measured in one pass of the SSIM window (the
// window's cost does not depend on how many masks average it); a region
// measured on its own image has its own pass. The error statistics are per
// pixel, and every image equals `test` on its regions' pixels: so every
// region's are one pass over `test`.
ImageMetrics compare_images(const ImageF& test, const ImageF& ref, const Regions& regions,
                            const std::vector<JobRegion>& job) {
  const ImageF t = with_unmeasured_from(test, ref, regions.measured);
  std::vector<Pass> passes;
  std::vector<const std::vector<uint8_t>*> shared, measured;
  for (const JobRegion& r : job) {
    passes.push_back(pass_of(r, t, ref, regions));
    if (passes.back() != Pass::Empty) measured.push_back(&r.mask);
    if (passes.back() == Pass::Shared) shared.push_back(&r.mask);
  }
  const std::vector<ErrorStats> stats = compare_without_ssim(test, ref, measured);
  const bool fits = ssim_fits(test);
  const std::vector<double> shared_ssim =
      fits && !shared.empty() ? ssim(t, ref, 1.0, shared) : std::vector<double>{};
  ImageMetrics m;
  size_t next = 0, next_shared = 0;
  for (size_t i = 0; i < job.size(); ++i) {
    RegionStats& slot = record::find_region(job[i].region->key)->slot(m);
    if (passes[i] == Pass::Empty) {
      slot = no_pixels();
      continue;
    }
    slot = stats[next++];
    const double own_ssim =
        passes[i] == Pass::Shared
            ? (fits ? shared_ssim[next_shared++] : std::nan(""))
            : (fits ? ssim(with_unmeasured_from(test, ref, job[i].mask), ref, 1.0, &job[i].mask)
                    : std::nan(""));
    if (slot.pixel_count > 0) slot.ssim = own_ssim;
  }
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

// Each region's mean of the FLIP map of test against ref, the map computed
// as the region's SSIM is (compare_images): one map of the technique's
// measured pixels for the regions that share it, and for the others a map
// with every pixel outside the region from ref, made only where it differs
// from a map made already (`known`, and the shared one: flip_reuse.h). A
// region with no pixel of its own pass has no FLIP.
void add_flip_means(ImageMetrics& m, const ImageF& test, const ImageF& ref, const Regions& regions,
                    const std::vector<JobRegion>& job, double pixels_per_degree,
                    std::vector<KnownFlipMap> known = {}) {
  const ImageF t = with_unmeasured_from(test, ref, regions.measured);
  const ImageF map = flip_map_reusing(ref, t, nullptr, known, pixels_per_degree);
  known.push_back({&t, &map});
  for (const JobRegion& r : job) {
    RegionStats& slot = record::find_region(r.region->key)->slot(m);
    switch (pass_of(r, t, ref, regions)) {
      case Pass::Shared:
        slot.flip_mean = masked_mean(map, r.mask);
        break;
      case Pass::Own:
        slot.flip_mean = masked_mean(flip_map_reusing(ref, with_unmeasured_from(test, ref, r.mask),
                                                      &r.mask, known, pixels_per_degree),
                                     r.mask);
        break;
      case Pass::Empty:
        break;
    }
  }
}

// The image as shaded.png holds it (8 bits a value), decoded from sRGB: what
// FLIP's own tool reads from the file, so that the figure can be recomputed
// from it. A byte's decoded value is looked up: linear_from_srgb's own value
// for it.
ImageF as_flip_reads_png(const ImageF& shaded) {
  static const std::array<float, 256> decoded = [] {
    ImageF bytes(256, 1, 1);
    for (int b = 0; b < 256; ++b)
      bytes.data[static_cast<std::size_t>(b)] = static_cast<float>(b) / 255.0f;
    const ImageF linear = linear_from_srgb(bytes);
    std::array<float, 256> table{};
    std::copy(linear.data.begin(), linear.data.end(), table.begin());
    return table;
  }();
  ImageF q = shaded;
  const std::size_t nc = static_cast<std::size_t>(q.channels);
  for (std::size_t i = 0; i < q.data.size(); ++i) {
    const uint8_t byte = io::png_byte(q.data[i]);
    // A 4th channel (alpha) is not sRGB-encoded: linear_from_srgb keeps it.
    q.data[i] = nc == 4 && i % 4 == 3 ? static_cast<float>(byte) / 255.0f : decoded[byte];
  }
  return q;
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
  const std::vector<JobRegion> of_visibility = job_regions(regions, visibility, true);
  const std::vector<JobRegion> of_shaded = job_regions(regions, visibility, false);
  MetricsRecord m{compare_images(visibility, ref_visibility, regions, of_visibility),
                  compare_images(shaded, ref_shaded, regions, of_shaded)};
  add_flip_means(m.visibility, visibility, ref_visibility, regions, of_visibility,
                 flip_pixels_per_degree);
  const ImageF shaded_png = as_flip_reads_png(shaded), ref_png = as_flip_reads_png(ref_shaded);
  // As FLIP's tool compares the two PNGs: every pixel, nothing replaced.
  FlipResult whole = flip(ref_png, shaded_png, flip_pixels_per_degree);
  add_flip_means(m.shaded, shaded_png, ref_png, regions, of_shaded, flip_pixels_per_degree,
                 {{&shaded_png, &whole.error}});
  m.flip_shaded = whole.mean;
  if (flip_map != nullptr) *flip_map = std::move(whole.error);
  return m;
}

ImageMetrics measure_visibility(const ImageF& visibility, const ImageF& ref_visibility,
                                const Regions& regions, double flip_pixels_per_degree) {
  const std::vector<JobRegion> job = job_regions(regions, visibility, false);
  ImageMetrics m = compare_images(visibility, ref_visibility, regions, job);
  add_flip_means(m, visibility, ref_visibility, regions, job, flip_pixels_per_degree);
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
