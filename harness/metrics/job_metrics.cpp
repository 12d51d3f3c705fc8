#include "metrics/job_metrics.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "metrics/flip.h"
#include "metrics/flip_reuse.h"
#include "metrics/geometry_region.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "metrics/prepared_reference.h"
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
  const std::vector<uint8_t>* mask;
};

// Each per-job region's pixels, made once from the job's V, at its index in
// `regions.masks` (empty for the others).
std::vector<std::vector<uint8_t>> per_job_masks(const Regions& regions, const ImageF& visibility) {
  std::vector<std::vector<uint8_t>> out(regions.masks.size());
  for (size_t i = 0; i < out.size(); ++i)
    if (regions.masks[i].per_job) out[i] = job_mask(regions.masks[i], visibility, regions);
  return out;
}

// The regions one image of a job is measured over, in catalogue order:
// `visibility_only` ones when `with_visibility_only`. `made` is
// per_job_masks'.
std::vector<JobRegion> job_regions(const Regions& regions,
                                   const std::vector<std::vector<uint8_t>>& made,
                                   bool with_visibility_only) {
  std::vector<JobRegion> out;
  for (size_t i = 0; i < regions.masks.size(); ++i) {
    const RegionMask& r = regions.masks[i];
    if (with_visibility_only || !r.visibility_only)
      out.push_back({&r, r.per_job ? &made[i] : &r.mask});
  }
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
  if (count_ones(*r.mask) == 0) return Pass::Empty;
  return mask_within(*r.mask, regions.measured) && matches_outside(t, ref, *r.mask) ? Pass::Shared
                                                                                    : Pass::Own;
}

// How each region of one image of a job is measured: `t`, the technique's
// measured pixels with the reference's values elsewhere, shared by the
// regions that share a pass; each region's pass; and a region measured on
// its own, its own image (the technique's values inside it, the
// reference's outside). Its SSIM and its FLIP use the same images.
struct Passes {
  ImageF t;
  std::vector<Pass> of;
  std::vector<ImageF> own;  // empty but for Pass::Own
};

Passes passes_of(const ImageF& test, const ImageF& ref, const Regions& regions,
                 const std::vector<JobRegion>& job) {
  Passes p;
  p.t = with_unmeasured_from(test, ref, regions.measured);
  for (const JobRegion& r : job) {
    p.of.push_back(pass_of(r, p.t, ref, regions));
    p.own.push_back(p.of.back() == Pass::Own ? with_unmeasured_from(test, ref, *r.mask) : ImageF());
  }
  return p;
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
ImageMetrics compare_images(const ImageF& test, const ImageF& ref,
                            const std::vector<JobRegion>& job, const Passes& passes) {
  std::vector<const std::vector<uint8_t>*> shared, measured;
  for (size_t i = 0; i < job.size(); ++i) {
    if (passes.of[i] != Pass::Empty) measured.push_back(job[i].mask);
    if (passes.of[i] == Pass::Shared) shared.push_back(job[i].mask);
  }
  const std::vector<ErrorStats> stats = compare_without_ssim(test, ref, measured);
  const bool fits = ssim_fits(test);
  const std::vector<double> shared_ssim =
      fits && !shared.empty() ? ssim(passes.t, ref, 1.0, shared) : std::vector<double>{};
  ImageMetrics m;
  size_t next = 0, next_shared = 0;
  for (size_t i = 0; i < job.size(); ++i) {
    RegionStats& slot = record::find_region(job[i].region->key)->slot(m);
    if (passes.of[i] == Pass::Empty) {
      slot = no_pixels();
      continue;
    }
    slot = stats[next++];
    const double own_ssim =
        passes.of[i] == Pass::Shared
            ? (fits ? shared_ssim[next_shared++] : std::nan(""))
            : (fits ? ssim(passes.own[i], ref, 1.0, job[i].mask) : std::nan(""));
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

// Each region's mean of the FLIP map of its image against the reference
// (`prepared`, its FLIP half), the images those of its SSIM (`passes`):
// one map of `t` for the regions that share it, and for a region measured
// on its own image a map made only where that image differs from a map
// made already (`known`, and t's: flip_reuse.h). A region with no pixel of
// its own pass has no FLIP.
void add_flip_means(ImageMetrics& m, const FlipReference& prepared,
                    const std::vector<JobRegion>& job, const Passes& passes,
                    std::vector<KnownFlipMap> known = {}) {
  const ImageF map = flip_map_reusing(prepared, passes.t, nullptr, known);
  known.push_back({&passes.t, &map});
  for (size_t i = 0; i < job.size(); ++i) {
    RegionStats& slot = record::find_region(job[i].region->key)->slot(m);
    switch (passes.of[i]) {
      case Pass::Shared:
        slot.flip_mean = masked_mean(map, *job[i].mask);
        break;
      case Pass::Own:
        slot.flip_mean = masked_mean(flip_map_reusing(prepared, passes.own[i], job[i].mask, known),
                                     *job[i].mask);
        break;
      case Pass::Empty:
        break;
    }
  }
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

MetricsRecord measure(const ImageF& visibility, const ImageF& shaded,
                      const PreparedReference& reference, const Regions& regions,
                      ImageF* flip_map) {
  const ImageF &ref_visibility = reference.visibility(), &ref_shaded = reference.shaded();
  const std::vector<std::vector<uint8_t>> made = per_job_masks(regions, visibility);
  const std::vector<JobRegion> of_visibility = job_regions(regions, made, true);
  const std::vector<JobRegion> of_shaded = job_regions(regions, made, false);
  const Passes visibility_passes = passes_of(visibility, ref_visibility, regions, of_visibility);
  MetricsRecord m{compare_images(visibility, ref_visibility, of_visibility, visibility_passes),
                  compare_images(shaded, ref_shaded, of_shaded,
                                 passes_of(shaded, ref_shaded, regions, of_shaded))};
  add_flip_means(m.visibility, reference.flip_visibility(), of_visibility, visibility_passes);
  // FLIP reads the shaded images as their PNGs hold them.
  const ImageF shaded_png = as_flip_reads_png(shaded);
  // As FLIP's tool compares the two PNGs: every pixel, nothing replaced.
  FlipResult whole = flip(reference.flip_shaded_png(), shaded_png);
  add_flip_means(m.shaded, reference.flip_shaded_png(), of_shaded,
                 passes_of(shaded_png, reference.shaded_png(), regions, of_shaded),
                 {{&shaded_png, &whole.error}});
  m.flip_shaded = whole.mean;
  if (flip_map != nullptr) *flip_map = std::move(whole.error);
  return m;
}

MetricsRecord measure(const ImageF& visibility, const ImageF& shaded, const ImageF& ref_visibility,
                      const ImageF& ref_shaded, const Regions& regions,
                      double flip_pixels_per_degree, ImageF* flip_map) {
  return measure(visibility, shaded,
                 PreparedReference(ref_visibility, ref_shaded, flip_pixels_per_degree), regions,
                 flip_map);
}

ImageMetrics measure_visibility(const ImageF& visibility, const ImageF& ref_visibility,
                                const FlipReference& ref_flip, const Regions& regions) {
  const std::vector<std::vector<uint8_t>> made = per_job_masks(regions, visibility);
  const std::vector<JobRegion> job = job_regions(regions, made, false);
  const Passes passes = passes_of(visibility, ref_visibility, regions, job);
  ImageMetrics m = compare_images(visibility, ref_visibility, job, passes);
  add_flip_means(m, ref_flip, job, passes);
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
