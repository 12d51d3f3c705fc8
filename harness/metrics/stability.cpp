#include "metrics/stability.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sb::metrics {

using core::ImageF;

namespace {

void check_pair(const ImageF& a, const ImageF& b, const std::vector<uint8_t>* mask,
                const char* what) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels)
    throw std::invalid_argument(std::string(what) + ": images of different shapes");
  if (a.channels != 1) throw std::invalid_argument(std::string(what) + ": expected one channel");
  if (mask && mask->size() != a.pixel_count())
    throw std::invalid_argument(std::string(what) + ": mask of another size");
}

// numpy.percentile's default (linear) interpolation of sorted values.
double percentile(std::vector<double>& values, double q) {
  if (values.empty()) return 0.0;
  const double rank = q / 100.0 * double(values.size() - 1);
  const size_t lo = size_t(std::floor(rank));
  const size_t hi = std::min(lo + 1, values.size() - 1);
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(lo), values.end());
  const double a = values[lo];
  const double b =
      hi == lo ? a : *std::min_element(values.begin() + std::ptrdiff_t(lo) + 1, values.end());
  return a + (rank - double(lo)) * (b - a);
}

}  // namespace

FlickerStats flicker(const std::vector<ImageF>& frames, const std::vector<uint8_t>* mask) {
  if (frames.size() < 2) throw std::invalid_argument("flicker: fewer than two frames");
  for (size_t k = 1; k < frames.size(); ++k) check_pair(frames[k], frames[0], mask, "flicker");
  FlickerStats out;
  out.frames = int(frames.size());
  std::vector<double> diffs;
  for (size_t k = 1; k < frames.size(); ++k)
    for (size_t i = 0; i < frames[0].pixel_count(); ++i) {
      if (mask && !(*mask)[i]) continue;
      const double a = frames[k].data[i], b = frames[k - 1].data[i];
      if (!std::isfinite(a) || !std::isfinite(b)) {
        ++out.nonfinite;
        continue;
      }
      diffs.push_back(std::fabs(a - b));
    }
  out.samples = diffs.size();
  if (diffs.empty()) return out;
  double sum = 0.0;
  for (double d : diffs) sum += d;
  out.mean = sum / double(diffs.size());
  out.max = *std::max_element(diffs.begin(), diffs.end());
  out.frac_over_005 =
      double(std::count_if(diffs.begin(), diffs.end(), [](double d) { return d > 0.05; })) /
      double(diffs.size());
  out.p99 = percentile(diffs, 99.0);
  return out;
}

Sensitivity sensitivity(const ImageF& v_plus, const ImageF& v_minus, double value, double h,
                        const std::vector<uint8_t>* mask) {
  if (!(h > 0.0)) throw std::invalid_argument("sensitivity: step must be > 0");
  check_pair(v_plus, v_minus, mask, "sensitivity");
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < v_plus.pixel_count(); ++i) {
    if (mask && !(*mask)[i]) continue;
    sum += std::fabs(double(v_plus.data[i]) - double(v_minus.data[i])) / (2.0 * h);
    ++n;
  }
  Sensitivity s;
  s.step = h;
  s.dv_dp = n ? sum / double(n) : 0.0;
  s.relative = s.dv_dp * std::fabs(value);
  return s;
}

}  // namespace sb::metrics
