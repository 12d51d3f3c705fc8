#include "metrics/metrics.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>

#include "metrics/metrics_detail.h"

namespace sb::metrics {

using core::ImageF;

namespace detail {

using core::ImageF;

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

bool ssim_fits(const ImageF& test) {
  return test.width >= 2 * kSsimRadius + 1 && test.height >= 2 * kSsimRadius + 1;
}

namespace {

// One row's sums for one mask, in the order the values come (row-major,
// then channel): the order a plain loop over the image would add them in.
struct RowSums {
  size_t pixels = 0, nonfinite = 0, over001 = 0, over005 = 0, over01 = 0;
  double abs = 0, sq = 0, sgn = 0;
  double max_error = 0;
  int max_x = -1, max_channel = -1;
};

// compare() but SSIM, left at 1 (NaN when no pixel is included), for every
// mask in one pass over the pixels: each value's error is worked out once.
// Rows run in parallel into per-row sums, added in row order afterwards, so
// every figure is what one sequential loop per mask gives, bit for bit.
std::vector<ErrorStats> compare_errors(const ImageF& test, const ImageF& ref,
                                       const std::vector<const std::vector<uint8_t>*>& masks) {
  detail::check_same_shape(test, ref, "metrics::compare");
  for (const auto* mask : masks) detail::check_mask(test, mask, "metrics::compare");
  const int nc = test.channels;
  const size_t n = masks.size(), height = static_cast<size_t>(test.height);
  std::vector<RowSums> rows(n * height);
  tbb::parallel_for(
      tbb::blocked_range<int>(0, test.height, 8), [&](const tbb::blocked_range<int>& r) {
        // One row's errors, worked out once for every mask.
        const size_t row_values = static_cast<size_t>(test.width) * nc;
        std::vector<double> f(row_values), sgn(row_values),
            pixel_max(static_cast<size_t>(test.width));
        std::vector<uint8_t> finite(row_values);
        for (int y = r.begin(); y != r.end(); ++y) {
          const size_t first = static_cast<size_t>(y) * row_values;
          for (size_t i = 0; i < row_values; ++i) {
            const float t = test.data[first + i], rv = ref.data[first + i];
            finite[i] = value_error(t, rv, f[i]) ? 1 : 0;
            sgn[i] = finite[i] && std::isfinite(t) ? double(t) - double(rv) : 0.0;
          }
          for (int x = 0; x < test.width; ++x) {
            double most = 0;
            for (int c = 0; c < nc; ++c) most = std::max(most, f[static_cast<size_t>(x) * nc + c]);
            pixel_max[static_cast<size_t>(x)] = most;
          }
          const size_t row_pixel = static_cast<size_t>(y) * test.width;
          for (size_t m = 0; m < n; ++m) {
            const uint8_t* mask = masks[m] != nullptr ? masks[m]->data() + row_pixel : nullptr;
            // Summed in a local, stored once: through the reference into
            // `rows` every add went through memory (the compiler cannot
            // tell it from f's), which bound the whole pass.
            RowSums s;
            for (int x = 0; x < test.width; ++x) {
              if (mask != nullptr && mask[x] == 0) continue;
              ++s.pixels;
              for (int c = 0; c < nc; ++c) {
                const size_t i = static_cast<size_t>(x) * nc + c;
                if (finite[i]) {
                  s.abs += f[i];
                  s.sq += f[i] * f[i];
                  s.sgn += sgn[i];
                } else {
                  ++s.nonfinite;
                }
                // !(f <= max) like OIIO: first occurrence wins ties.
                if (!(f[i] <= s.max_error)) {
                  s.max_error = f[i];
                  s.max_x = x;
                  s.max_channel = c;
                }
              }
              const double most = pixel_max[static_cast<size_t>(x)];
              s.over001 += most > 0.01 ? 1 : 0;
              s.over005 += most > 0.05 ? 1 : 0;
              s.over01 += most > 0.1 ? 1 : 0;
            }
            rows[m * height + static_cast<size_t>(y)] = s;
          }
        }
      });
  std::vector<ErrorStats> out(n);
  for (size_t m = 0; m < n; ++m) {
    ErrorStats& s = out[m];
    size_t over001 = 0, over005 = 0, over01 = 0;
    double sum_abs = 0, sum_sq = 0, sum_signed = 0;
    for (size_t y = 0; y < height; ++y) {
      const RowSums& row = rows[m * height + y];
      // Per-row partial sums limit the cancellation error, as OIIO's batches.
      s.pixel_count += static_cast<std::int64_t>(row.pixels);
      s.nonfinite_count += static_cast<std::int64_t>(row.nonfinite);
      over001 += row.over001;
      over005 += row.over005;
      over01 += row.over01;
      sum_abs += row.abs;
      sum_sq += row.sq;
      sum_signed += row.sgn;
      if (!(row.max_error <= s.max_error)) {  // the first row to reach it
        s.max_error = row.max_error;
        s.max_x = row.max_x;
        s.max_y = static_cast<int>(y);
        s.max_channel = row.max_channel;
      }
    }
    if (s.pixel_count == 0) {
      // Nothing to measure: every figure is undefined.
      s.rmse = s.mae = s.max_error = s.psnr = s.ssim = s.mean_signed = kNaN;
      s.frac_over_001 = s.frac_over_005 = s.frac_over_01 = kNaN;
      continue;
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
  }
  return out;
}

}  // namespace

ErrorStats compare(const ImageF& test, const ImageF& ref, const std::vector<uint8_t>* mask) {
  ErrorStats s = compare_errors(test, ref, {mask}).front();
  if (s.pixel_count > 0) s.ssim = ssim_fits(test) ? ssim(test, ref, 1.0, mask) : kNaN;
  return s;
}

std::vector<ErrorStats> compare_without_ssim(
    const ImageF& test, const ImageF& ref, const std::vector<const std::vector<uint8_t>*>& masks) {
  return compare_errors(test, ref, masks);
}

std::vector<ErrorStats> compare(const ImageF& test, const ImageF& ref,
                                const std::vector<const std::vector<uint8_t>*>& masks) {
  std::vector<ErrorStats> out = compare_errors(test, ref, masks);
  if (!ssim_fits(test)) {
    for (ErrorStats& s : out)
      if (s.pixel_count > 0) s.ssim = kNaN;
    return out;
  }
  const std::vector<double> ssim_values = ssim(test, ref, 1.0, masks);
  for (size_t i = 0; i < out.size(); ++i)
    if (out[i].pixel_count > 0) out[i].ssim = ssim_values[i];
  return out;
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
