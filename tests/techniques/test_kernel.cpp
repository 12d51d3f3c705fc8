#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "common/kernel.h"

namespace sb::techniques {
namespace {

TEST(Kernel, BoxWeightsAreEqualAndSumToOne) {
  for (int k : {1, 3, 9, 19, 63}) {
    const auto w = kernel_weights(KernelShape::Box, k, 0.0f);
    ASSERT_EQ(w.size(), size_t(k));
    for (float v : w) EXPECT_FLOAT_EQ(v, 1.0f / float(k));
    EXPECT_NEAR(std::accumulate(w.begin(), w.end(), 0.0), 1.0, 1e-6);
  }
}

// OpenCV's getGaussianKernel(5, 1.0) is 0.05448868, 0.24420134, 0.40261995,
// 0.24420134, 0.05448868 (its documented formula, evaluated).
TEST(Kernel, GaussianMatchesOpenCvGetGaussianKernel) {
  const auto w = kernel_weights(KernelShape::Gauss, 5, 1.0f);
  const double expected[5] = {0.05448868, 0.24420134, 0.40261995, 0.24420134, 0.05448868};
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(w[size_t(i)], expected[i], 1e-6) << i;
}

TEST(Kernel, GaussianSigmaDefaultsToOpenCvsRule) {
  EXPECT_FLOAT_EQ(gaussian_sigma(3, 0.0f), 0.8f);
  EXPECT_FLOAT_EQ(gaussian_sigma(9, 0.0f), 0.3f * 3.0f + 0.8f);
  EXPECT_FLOAT_EQ(gaussian_sigma(9, 2.5f), 2.5f);
  const auto w = kernel_weights(KernelShape::Gauss, 13, 0.0f);
  EXPECT_NEAR(std::accumulate(w.begin(), w.end(), 0.0), 1.0, 1e-6);
  for (size_t i = 0; i < w.size(); ++i) EXPECT_FLOAT_EQ(w[i], w[w.size() - 1 - i]);
  for (size_t i = 0; i + 1 <= w.size() / 2; ++i) EXPECT_LT(w[i], w[i + 1]);
}

TEST(Kernel, RejectsEvenAndOversizedKernels) {
  EXPECT_THROW(kernel_weights(KernelShape::Box, 4, 0.0f), std::logic_error);
  EXPECT_THROW(kernel_weights(KernelShape::Box, kMaxKernelTaps + 2, 0.0f), std::logic_error);
}

}  // namespace
}  // namespace sb::techniques
