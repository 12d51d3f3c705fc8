#pragma once
// Image-comparison metrics for shadow images: error statistics that agree with
// OpenImageIO's ImageBufAlgo::compare / idiff, SSIM that agrees with
// scikit-image, penumbra masks and error heat maps.
//
// All functions take images of the same shape (else std::invalid_argument).
// A mask, where accepted, has one byte per pixel (row-major, row 0 on top);
// nonzero means "include" (else std::invalid_argument on a size mismatch).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "record/metrics_record.h"

namespace sb::metrics {

// The statistics of one image over one region of pixels are the record's own
// (record::RegionStats, each figure's meaning at its member): compare()
// computes them straight into it. flip_mean is left unset (metrics/flip.h).
using ErrorStats = record::RegionStats;

// Error statistics of test against ref. Every figure, SSIM included, is
// restricted to the masked pixels when a mask is given.
ErrorStats compare(const core::ImageF& test, const core::ImageF& ref,
                   const std::vector<uint8_t>* mask = nullptr);

// compare() over several masks of the same pair of images, in one pass of
// the SSIM window (the map is the same whatever the mask; only which of its
// pixels are averaged differs): out[i] == compare(test, ref, masks[i]),
// bit for bit. A null mask is every pixel.
std::vector<ErrorStats> compare(const core::ImageF& test, const core::ImageF& ref,
                                const std::vector<const std::vector<uint8_t>*>& masks);

// compare() over several masks, SSIM left out (1; NaN over no pixel). Its
// figures are per pixel: over a mask they depend only on the mask's pixels.
std::vector<ErrorStats> compare_without_ssim(const core::ImageF& test, const core::ImageF& ref,
                                             const std::vector<const std::vector<uint8_t>*>& masks);

// Whether SSIM's window fits the image (else compare() gives SSIM NaN).
bool ssim_fits(const core::ImageF& image);

// SSIM constants and window (Wang et al. 2004, as scikit-image's
// structural_similarity(gaussian_weights=True, sigma=1.5,
// use_sample_covariance=False)).
inline constexpr int kSsimRadius = 5;  // int(3.5 * 1.5 + 0.5): 11x11 Gaussian window
inline constexpr double kSsimSigma = 1.5;
inline constexpr double kSsimK1 = 0.01;
inline constexpr double kSsimK2 = 0.03;

// Mean SSIM. Per channel: Gaussian-weighted local means, population
// variances and covariance (scipy.ndimage 'reflect' borders), the SSIM map,
// then its mean over the pixels that are at least kSsimRadius away from
// every border (skimage's crop(S, 5)) and, with a mask, also masked. The
// result is the mean of those per-channel means (skimage with channel_axis=-1).
// Computed in double. Returns NaN when the mask leaves no pixel in that
// interior. Throws std::invalid_argument when width or height < 11 (as
// skimage does) or data_range <= 0.
double ssim(const core::ImageF& a, const core::ImageF& b, double data_range = 1.0,
            const std::vector<uint8_t>* mask = nullptr);

// ssim() over several masks in one pass: out[i] == ssim(a, b, data_range,
// masks[i]), bit for bit.
std::vector<double> ssim(const core::ImageF& a, const core::ImageF& b, double data_range,
                         const std::vector<const std::vector<uint8_t>*>& masks);

// The full SSIM map (same shape as the inputs, one value per channel), border
// pixels included (computed with reflected borders, as skimage's full=True).
core::ImageF ssim_map(const core::ImageF& a, const core::ImageF& b, double data_range = 1.0);

// Pixels in the reference penumbra: some channel of the visibility V has
// eps < V < 1 - eps.
std::vector<uint8_t> penumbra_mask(const core::ImageF& reference_visibility, float eps = 1e-6f);

// The soft pixels of either image: penumbra_mask(a) OR penumbra_mask(b). With
// a technique and the reference, it adds what the reference's penumbra
// misses: light bleeding into a true umbra and blur outside the true penumbra.
std::vector<uint8_t> soft_union_mask(const core::ImageF& a, const core::ImageF& b,
                                     float eps = 1e-6f);

// RGB heat map of the per-pixel error (max over channels of |test - ref|)
// through an inferno-like ramp: 0 -> black, >= full_scale -> the brightest
// colour (pale yellow); non-finite errors are shown as full scale. Values are
// display-encoded (sRGB) in [0,1], meant for write_png. Throws
// std::invalid_argument when full_scale is not > 0.
core::ImageF error_heatmap(const core::ImageF& test, const core::ImageF& ref, float full_scale);

// The ramp itself: t in [0,1] (clamped) to display RGB.
void heatmap_colour(float t, float rgb[3]);

}  // namespace sb::metrics
