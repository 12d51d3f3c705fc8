#include "metrics/metrics.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>

#include "metrics/metrics_detail.h"

namespace sb::metrics {

namespace detail {

void check_same_shape(const ImageF& a, const ImageF& b, const char* fn) {
  if (!a.same_shape(b)) {
    auto shape = [](const ImageF& i) {
      return std::to_string(i.width) + "x" + std::to_string(i.height) + "x" +
             std::to_string(i.channels);
    };
    throw std::invalid_argument(std::string(fn) + ": image shapes differ (" + shape(a) + " vs " +
                                shape(b) + ")");
  }
  if (a.data.size() != a.pixel_count() * static_cast<size_t>(a.channels) ||
      b.data.size() != a.data.size()) {
    throw std::invalid_argument(std::string(fn) + ": image data size does not match its shape");
  }
}

void check_mask(const ImageF& a, const std::vector<uint8_t>* mask, const char* fn) {
  if (mask && mask->size() != a.pixel_count()) {
    throw std::invalid_argument(std::string(fn) + ": mask has " + std::to_string(mask->size()) +
                                " entries, image has " + std::to_string(a.pixel_count()) +
                                " pixels");
  }
}

}  // namespace detail

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Error of one value pair. Returns false (and f = inf) for a non-finite
// mismatch, which is kept out of the sums.
inline bool value_error(float t, float r, double& f) {
  if (std::isfinite(t) && std::isfinite(r)) {
    // Subtract in float as OIIO does, so max locations agree on ties.
    f = std::fabs(static_cast<double>(t - r));
    return true;
  }
  const bool match = (std::isnan(t) && std::isnan(r)) || t == r;
  f = match ? 0.0 : kInf;
  return match;
}

}  // namespace

ErrorStats compare(const ImageF& test, const ImageF& ref, const std::vector<uint8_t>* mask) {
  detail::check_same_shape(test, ref, "metrics::compare");
  detail::check_mask(test, mask, "metrics::compare");
  ErrorStats s;
  const int nc = test.channels;
  size_t over001 = 0, over005 = 0, over01 = 0;
  double sum_abs = 0, sum_sq = 0, sum_signed = 0;
  for (int y = 0; y < test.height; ++y) {
    // Per-row partial sums limit the cancellation error, as OIIO's batches.
    double row_abs = 0, row_sq = 0, row_signed = 0;
    for (int x = 0; x < test.width; ++x) {
      const size_t p = static_cast<size_t>(y) * test.width + x;
      if (mask && (*mask)[p] == 0) continue;
      ++s.pixel_count;
      double pixel_max = 0;
      for (int c = 0; c < nc; ++c) {
        const size_t i = p * nc + c;
        double f;
        if (value_error(test.data[i], ref.data[i], f)) {
          row_abs += f;
          row_sq += f * f;
          if (std::isfinite(test.data[i])) row_signed += double(test.data[i]) - double(ref.data[i]);
        } else {
          ++s.nonfinite_count;
        }
        // !(f <= max) like OIIO: first occurrence wins ties.
        if (!(f <= s.max_error)) {
          s.max_error = f;
          s.max_x = x;
          s.max_y = y;
          s.max_channel = c;
        }
        pixel_max = std::max(pixel_max, f);
      }
      over001 += pixel_max > 0.01 ? 1 : 0;
      over005 += pixel_max > 0.05 ? 1 : 0;
      over01 += pixel_max > 0.1 ? 1 : 0;
    }
    sum_abs += row_abs;
    sum_sq += row_sq;
    sum_signed += row_signed;
  }
  if (s.pixel_count == 0) {
    // Nothing to measure: every figure is undefined.
    s.rmse = s.mae = s.max_error = s.psnr = s.ssim = s.mean_signed = kNaN;
    s.frac_over_001 = s.frac_over_005 = s.frac_over_01 = kNaN;
    return s;
  }
  const double nvals = static_cast<double>(s.pixel_count) * nc;
  const double npix = static_cast<double>(s.pixel_count);
  s.mae = sum_abs / nvals;
  s.mean_signed = sum_signed / nvals;
  s.rmse = std::sqrt(sum_sq / nvals);
  s.psnr = s.rmse == 0 ? kInf : 20.0 * std::log10(1.0 / s.rmse);
  s.frac_over_001 = static_cast<double>(over001) / npix;
  s.frac_over_005 = static_cast<double>(over005) / npix;
  s.frac_over_01 = static_cast<double>(over01) / npix;
  const bool ssim_fits = test.width >= 2 * kSsimRadius + 1 && test.height >= 2 * kSsimRadius + 1;
  s.ssim = ssim_fits ? ssim(test, ref, 1.0, mask) : kNaN;
  return s;
}

std::vector<uint8_t> penumbra_mask(const ImageF& v, float eps) {
  std::vector<uint8_t> mask(v.pixel_count(), 0);
  const size_t nc = static_cast<size_t>(v.channels);
  for (size_t p = 0; p < mask.size(); ++p) {
    for (size_t c = 0; c < nc; ++c) {
      const float x = v.data[p * nc + c];
      if (x > eps && x < 1.0f - eps) {
        mask[p] = 1;
        break;
      }
    }
  }
  return mask;
}

std::vector<uint8_t> soft_union_mask(const ImageF& a, const ImageF& b, float eps) {
  detail::check_same_shape(a, b, "metrics::soft_union_mask");
  std::vector<uint8_t> mask = penumbra_mask(a, eps);
  const std::vector<uint8_t> other = penumbra_mask(b, eps);
  for (size_t p = 0; p < mask.size(); ++p) mask[p] = uint8_t(mask[p] | other[p]);
  return mask;
}

void heatmap_colour(float t, float rgb[3]) {
  // matplotlib 'inferno' sampled at 10 even steps, the first made pure black.
  static constexpr float kRamp[][3] = {
      {0, 0, 0},     {27, 12, 65},   {74, 12, 107}, {120, 28, 109}, {165, 44, 96},
      {207, 68, 70}, {237, 105, 37}, {251, 155, 6}, {247, 209, 61}, {252, 255, 164},
  };
  constexpr int kLast = static_cast<int>(std::size(kRamp)) - 1;
  if (!(t > 0.0f)) t = 0.0f;  // NaN counts as 0 here; callers map it to full scale.
  t = std::min(t, 1.0f) * kLast;
  const int i = std::min(static_cast<int>(t), kLast - 1);
  const float f = t - static_cast<float>(i);
  for (int c = 0; c < 3; ++c) {
    rgb[c] = (kRamp[i][c] + f * (kRamp[i + 1][c] - kRamp[i][c])) / 255.0f;
  }
}

ImageF error_heatmap(const ImageF& test, const ImageF& ref, float full_scale) {
  detail::check_same_shape(test, ref, "metrics::error_heatmap");
  if (!(full_scale > 0.0f) || !std::isfinite(full_scale)) {
    throw std::invalid_argument("metrics::error_heatmap: full_scale must be a positive number");
  }
  ImageF out(test.width, test.height, 3);
  const size_t nc = static_cast<size_t>(test.channels);
  for (size_t p = 0; p < test.pixel_count(); ++p) {
    double e = 0;
    for (size_t c = 0; c < nc; ++c) {
      double f;
      value_error(test.data[p * nc + c], ref.data[p * nc + c], f);
      e = std::max(e, f);
    }
    const float t = static_cast<float>(std::min(e / full_scale, 1.0));
    heatmap_colour(t, &out.data[p * 3]);
  }
  return out;
}

}  // namespace sb::metrics
