// SSIM (Wang et al. 2004) computed to agree with scikit-image's
// structural_similarity(gaussian_weights=True, sigma=1.5,
// use_sample_covariance=False): 11-tap Gaussian (scipy truncate=3.5),
// scipy.ndimage 'reflect' borders, mean over the map cropped by 5 pixels.
//
// Each output row is produced on its own: a vertical 11-tap pass over the
// input rows gives the five windowed moments (a, b, a^2, b^2, ab) for the
// whole row, a horizontal 11-tap pass turns them into local means, and the
// SSIM formula is applied. Rows are independent, so they run under
// tbb::parallel_for with no shared intermediate images.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "metrics/metrics.h"
#include "metrics/metrics_detail.h"
#include "metrics/ssim_kernels.h"

namespace sb::metrics {

using core::ImageF;

namespace {

using detail::SimdPath;

constexpr int kR = kSsimRadius;
constexpr int kTaps = 2 * kR + 1;
static_assert(kTaps == detail::kSsimTaps);
// Elements per inner-loop chunk: five double accumulators stay in L1.
constexpr size_t kChunk = 256;

// scipy.ndimage._gaussian_kernel1d: exp(-x^2 / (2 sigma^2)), normalised to sum 1.
std::array<double, kTaps> gaussian_kernel() {
  std::array<double, kTaps> w{};
  double sum = 0;
  for (int i = 0; i < kTaps; ++i) {
    const double x = i - kR;
    w[i] = std::exp(-0.5 * x * x / (kSsimSigma * kSsimSigma));
    sum += w[i];
  }
  for (double& v : w) v /= sum;
  return w;
}

// scipy 'reflect' (d c b a | a b c d | d c b a); n > kR so one fold suffices.
inline int reflect(int i, int n) {
  if (i < 0) return -i - 1;
  if (i >= n) return 2 * n - 1 - i;
  return i;
}

struct SsimConstants {
  double c1, c2;
};

// Computes SSIM rows [y0, y1), columns [x0, x1), all channels, and calls
// sink(y, row) with row[(x - x0) * channels + c]. sink is called from TBB
// worker threads, once per row.
template <class Sink>
void ssim_rows(SimdPath path, const ImageF& a, const ImageF& b, SsimConstants k, int y0, int y1,
               int x0, int x1, Sink&& sink) {
  static const std::array<double, kTaps> w = gaussian_kernel();
  const int width = a.width, height = a.height;
  const size_t nc = static_cast<size_t>(a.channels);
  const size_t row_len = static_cast<size_t>(width) * nc;
  const size_t padded_len = (static_cast<size_t>(width) + 2 * kR) * nc;
  const size_t out_begin = static_cast<size_t>(x0) * nc;
  const size_t out_len = static_cast<size_t>(x1 - x0) * nc;

  tbb::parallel_for(tbb::blocked_range<int>(y0, y1, 4), [&](const tbb::blocked_range<int>& r) {
    // Moments after the vertical pass, with kR reflected pixels on each side.
    std::vector<double> moments(5 * padded_len);
    double* const m_a = moments.data();
    double* const m_b = m_a + padded_len;
    double* const m_aa = m_b + padded_len;
    double* const m_bb = m_aa + padded_len;
    double* const m_ab = m_bb + padded_len;
    std::vector<double> out(out_len);
    std::array<const float*, kTaps> rows_a{}, rows_b{}, chunk_a{}, chunk_b{};

    for (int y = r.begin(); y != r.end(); ++y) {
      for (int t = 0; t < kTaps; ++t) {
        const size_t src = static_cast<size_t>(reflect(y + t - kR, height)) * row_len;
        rows_a[t] = a.data.data() + src;
        rows_b[t] = b.data.data() + src;
      }
      // Vertical pass in L1-sized chunks: the five accumulators stay in cache.
      const size_t pad = static_cast<size_t>(kR) * nc;
      for (size_t i0 = 0; i0 < row_len; i0 += kChunk) {
        const size_t n = std::min(kChunk, row_len - i0);
        for (int t = 0; t < kTaps; ++t) {
          chunk_a[t] = rows_a[t] + i0;
          chunk_b[t] = rows_b[t] + i0;
        }
        const size_t o = pad + i0;
        detail::vertical_moments(path, chunk_a, chunk_b, w, n,
                                 {m_a + o, m_b + o, m_aa + o, m_bb + o, m_ab + o});
      }
      // Reflected columns, only needed when the output reaches the border.
      if (x0 < kR || x1 > width - kR) {
        for (double* m : {m_a, m_b, m_aa, m_bb, m_ab}) {
          for (int p = 1; p <= kR; ++p) {
            const size_t left = static_cast<size_t>(kR - p) * nc;
            const size_t left_src = static_cast<size_t>(kR + reflect(-p, width)) * nc;
            const size_t right = static_cast<size_t>(kR + width - 1 + p) * nc;
            const size_t right_src = static_cast<size_t>(kR + reflect(width - 1 + p, width)) * nc;
            for (size_t c = 0; c < nc; ++c) {
              m[left + c] = m[left_src + c];
              m[right + c] = m[right_src + c];
            }
          }
        }
      }
      // Horizontal pass + SSIM, again over chunks. Output x reads padded
      // pixels x .. x + 2kR.
      for (size_t j0 = 0; j0 < out_len; j0 += kChunk) {
        const size_t n = std::min(kChunk, out_len - j0);
        const size_t q = out_begin + j0;
        detail::horizontal_ssim(path, {m_a + q, m_b + q, m_aa + q, m_bb + q, m_ab + q}, nc, w, n,
                                k.c1, k.c2, out.data() + j0);
      }
      sink(y, out.data());
    }
  });
}

SsimConstants check_and_constants(const ImageF& a, const ImageF& b, double data_range,
                                  const char* fn) {
  detail::check_same_shape(a, b, fn);
  if (a.width < kTaps || a.height < kTaps) {
    throw std::invalid_argument(std::string(fn) + ": image is " + std::to_string(a.width) + "x" +
                                std::to_string(a.height) + ", SSIM needs at least " +
                                std::to_string(kTaps) + "x" + std::to_string(kTaps));
  }
  if (!(data_range > 0) || !std::isfinite(data_range)) {
    throw std::invalid_argument(std::string(fn) + ": data_range must be a positive number");
  }
  const double c1 = kSsimK1 * data_range, c2 = kSsimK2 * data_range;
  return {c1 * c1, c2 * c2};
}

}  // namespace

double ssim(const ImageF& a, const ImageF& b, double data_range, const std::vector<uint8_t>* mask) {
  return ssim(a, b, data_range, std::vector<const std::vector<uint8_t>*>{mask}).front();
}

std::vector<double> ssim(const ImageF& a, const ImageF& b, double data_range,
                         const std::vector<const std::vector<uint8_t>*>& masks) {
  return detail::ssim_on(detail::widest_simd_path(), a, b, data_range, masks);
}

ImageF ssim_map(const ImageF& a, const ImageF& b, double data_range) {
  return detail::ssim_map_on(detail::widest_simd_path(), a, b, data_range);
}

std::vector<double> detail::ssim_on(SimdPath path, const ImageF& a, const ImageF& b,
                                    double data_range,
                                    const std::vector<const std::vector<uint8_t>*>& masks) {
  const SsimConstants k = check_and_constants(a, b, data_range, "metrics::ssim");
  for (const auto* mask : masks) detail::check_mask(a, mask, "metrics::ssim");
  const int nc = a.channels;
  const int x0 = kR, x1 = a.width - kR;
  const size_t rows = static_cast<size_t>(a.height), n = masks.size();
  // Per-row partial results, summed in row order afterwards so the result
  // does not depend on how TBB split the work: [mask * rows + y].
  std::vector<double> row_sum(n * rows, 0.0);
  std::vector<size_t> row_count(n * rows, 0);
  // Only the rows where some mask has a pixel (every row when one is null):
  // a row's values depend on no other row's, and a row with no pixel adds
  // nothing.
  std::vector<uint8_t> wanted(rows, 0);
  for (int y = kR; y < a.height - kR; ++y)
    for (const auto* mask : masks) {
      if (mask != nullptr) {
        const auto row = mask->begin() + static_cast<std::ptrdiff_t>(y) * a.width;
        if (std::find_if(row + x0, row + x1, [](uint8_t v) { return v != 0; }) == row + x1)
          continue;
      }
      wanted[static_cast<size_t>(y)] = 1;
      break;
    }
  const auto sink = [&](int y, const double* row) {
    for (size_t m = 0; m < n; ++m) {
      const std::vector<uint8_t>* mask = masks[m];
      double sum = 0;
      size_t count = 0;
      for (int x = x0; x < x1; ++x) {
        if (mask && (*mask)[static_cast<size_t>(y) * a.width + x] == 0) continue;
        const double* px = row + static_cast<size_t>(x - x0) * nc;
        for (int c = 0; c < nc; ++c) sum += px[c];
        ++count;
      }
      row_sum[m * rows + static_cast<size_t>(y)] = sum;
      row_count[m * rows + static_cast<size_t>(y)] = count;
    }
  };
  for (int y0 = kR; y0 < a.height - kR;) {
    if (!wanted[static_cast<size_t>(y0)]) {
      ++y0;
      continue;
    }
    int y1 = y0;
    while (y1 < a.height - kR && wanted[static_cast<size_t>(y1)]) ++y1;
    ssim_rows(path, a, b, k, y0, y1, x0, x1, sink);
    y0 = y1;
  }
  std::vector<double> out(n);
  for (size_t m = 0; m < n; ++m) {
    double sum = 0;
    size_t count = 0;
    for (size_t y = 0; y < rows; ++y) {
      sum += row_sum[m * rows + y];
      count += row_count[m * rows + y];
    }
    // Every channel has the same pixel count, so the plain mean over all
    // values equals the mean of the per-channel means.
    out[m] = count == 0 ? std::numeric_limits<double>::quiet_NaN()
                        : sum / (static_cast<double>(count) * nc);
  }
  return out;
}

ImageF detail::ssim_map_on(SimdPath path, const ImageF& a, const ImageF& b, double data_range) {
  const SsimConstants k = check_and_constants(a, b, data_range, "metrics::ssim_map");
  ImageF map(a.width, a.height, a.channels);
  const size_t row_len = static_cast<size_t>(a.width) * a.channels;
  ssim_rows(path, a, b, k, 0, a.height, 0, a.width, [&](int y, const double* row) {
    float* dst = map.data.data() + static_cast<size_t>(y) * row_len;
    for (size_t i = 0; i < row_len; ++i) dst[i] = static_cast<float>(row[i]);
  });
  return map;
}

}  // namespace sb::metrics
