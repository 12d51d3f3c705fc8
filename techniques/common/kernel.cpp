#include "common/kernel.h"

#include <cmath>
#include <stdexcept>

namespace sb::techniques {

using core::float_param;
using core::int_param;
using core::odd;
using core::ParamSpec;
using core::with_sentinel;

KernelShape kernel_shape_from_string(const std::string& s) {
  if (s == "box") return KernelShape::Box;
  if (s == "gauss") return KernelShape::Gauss;
  throw std::logic_error("unknown kernel shape '" + s + "'");
}

float gaussian_sigma(int k, float sigma) {
  if (sigma > 0.0f) return sigma;
  return 0.3f * (0.5f * float(k - 1) - 1.0f) + 0.8f;
}

std::vector<float> kernel_weights(KernelShape shape, int k, float sigma) {
  if (k < 1 || k % 2 == 0 || k > kMaxKernelTaps)
    throw std::logic_error("kernel side must be odd and at most 63");
  std::vector<float> w(size_t(k), 1.0f);
  if (shape == KernelShape::Gauss) {
    const double s = gaussian_sigma(k, sigma);
    for (int i = 0; i < k; ++i) {
      const int offset = i - k / 2;  // taps are whole texels from the centre
      const double x = offset;
      w[size_t(i)] = float(std::exp(-0.5 * x * x / (s * s)));
    }
  }
  double sum = 0.0;
  for (float v : w) sum += v;
  for (float& v : w) v = float(v / sum);
  return w;
}

ParamSpec kernel_size_param(int default_k, const std::string& doc) {
  return odd(int_param("k", default_k, 1, kMaxKernelTaps, doc));
}

ParamSpec kernel_sigma_param() {
  return with_sentinel(
      float_param("sigma", 0.0, 0.0, 64.0,
                  "Gaussian sigma in texels; 0: 0.3*((k-1)/2-1)+0.8 (OpenCV's default)"),
      0.0);
}

}  // namespace sb::techniques
