#pragma once
// Filter kernels shared by the PCF variants and the separable prefilters:
// a k-tap 1D kernel whose outer product is the 2D one, so box and Gaussian
// PCF and the box and Gaussian prefilters read the same weights.
//
// What the kit guarantees here (shadowbench::shadow_kit, installed):
//   in     k, the kernel's side in taps (odd, 1..kMaxKernelTaps), and for
//          Gaussian weights sigma in texels (taps are one texel apart);
//   out    k weights, centre tap in the middle, summing to 1 up to float
//          rounding (box: each 1/k); std::logic_error for an even or too
//          large k (kernel_size_param() lets no such k through a config);
//   GL     none: plain CPU code;
//   cost   O(k).
#include <string>
#include <vector>

#include "core/params.h"

namespace sb::techniques {

// The weights' shape: equal (box) or Gaussian.
enum class KernelShape { Box, Gauss };
// The `kernel` parameter's value as a KernelShape: "box" | "gauss".
KernelShape kernel_shape_from_string(const std::string& s);

// The Gaussian's σ in texels; sigma <= 0 picks OpenCV getGaussianKernel's
// default for k taps, 0.3·((k−1)/2 − 1) + 0.8.
float gaussian_sigma(int k, float sigma);

// k (odd) weights summing to 1.
std::vector<float> kernel_weights(KernelShape shape, int k, float sigma);

// The largest k a kernel may have: the GLSL weight arrays hold this many.
constexpr int kMaxKernelTaps = 63;

// `k` (odd kernel side) and, for Gaussian kernels, `sigma`.
core::ParamSpec kernel_size_param(int default_k, const std::string& doc);
core::ParamSpec kernel_sigma_param();

}  // namespace sb::techniques
