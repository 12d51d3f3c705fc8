// pcf_jitter's taps are the documented function of (taps, seed)
// (shadow_map/jittered_disk.h): the same points with any standard library.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "shadow_map/jittered_disk.h"
#include "splitmix64_sequence.h"

namespace sb::techniques::shadow_map {
namespace {

// Tap i (before the outermost-first reversal) is at radius
// sqrt((i + u_i) / N), u_i the seed's SplitMix64 uniform i, and angle
// i·π(3 − √5), both in float. The radius is exact (IEEE sqrt); cos and sin
// come from the C library, hence the small tolerance.
TEST(JitteredDisk, TapsAreTheDocumentedFunctionOfSeedAndIndex) {
  for (const int n : {2, 32, 64})
    for (const unsigned seed : {0u, 1u, 12345u}) {
      SCOPED_TRACE("taps " + std::to_string(n) + ", seed " + std::to_string(seed));
      const std::vector<glm::vec2> taps = jittered_disk(n, seed);
      ASSERT_EQ(taps.size(), size_t(n));
      const std::vector<float> u = sbtest::splitmix64_uniforms(seed, n);
      for (int i = 0; i < n; ++i) {
        const glm::vec2 p = taps[size_t(n - 1 - i)];
        const float r = std::sqrt((float(i) + u[size_t(i)]) / float(n));
        const float phi = float(i) * (std::numbers::pi_v<float> * (3.0f - std::sqrt(5.0f)));
        EXPECT_NEAR(p.x, double(r) * std::cos(double(phi)), 1e-6) << "tap " << i;
        EXPECT_NEAR(p.y, double(r) * std::sin(double(phi)), 1e-6) << "tap " << i;
        EXPECT_FLOAT_EQ(std::hypot(p.x, p.y), r) << "tap " << i;
      }
    }
}

// Taps stay inside the disk and in their own equal-area rings, outermost
// first.
TEST(JitteredDisk, OneTapPerEqualAreaRingOutermostFirst) {
  const int n = 64;
  const std::vector<glm::vec2> taps = jittered_disk(n, 3);
  for (int k = 0; k < n; ++k) {
    const int ring = n - 1 - k;
    const float r2 = taps[size_t(k)].x * taps[size_t(k)].x + taps[size_t(k)].y * taps[size_t(k)].y;
    EXPECT_GE(r2 * float(n), float(ring) - 1e-4f) << "tap " << k;
    EXPECT_LE(r2 * float(n), float(ring + 1) + 1e-4f) << "tap " << k;
  }
}

}  // namespace
}  // namespace sb::techniques::shadow_map
