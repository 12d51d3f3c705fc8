// The kit's tap disks (common/sample_disks.h): pcf_jitter's jittered disk is
// the documented function of (taps, seed), the same points with any standard
// library; the Poisson disk keeps its documented spacing, stays in the unit
// disk, comes outermost first and is a function of (n, seed) alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "common/sample_disks.h"
#include "splitmix64_sequence.h"

namespace sb::techniques {
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

// Every pair of taps at least 2·sqrt(0.3/n) apart (the documented spacing,
// computed here from its formula, in double), for every count the GLSL
// arrays hold and several seeds; all inside the unit disk, outermost first.
TEST(PoissonDisk, KeepsTheDocumentedSpacingInsideTheDiskOutermostFirst) {
  for (int n = 1; n <= kMaxDiskTaps; ++n)
    for (const unsigned seed : {0u, 1u, 2u, 7u, 12345u}) {
      SCOPED_TRACE("taps " + std::to_string(n) + ", seed " + std::to_string(seed));
      const std::vector<glm::vec2> taps = poisson_disk(n, seed);
      ASSERT_EQ(taps.size(), size_t(n));
      const double spacing = 2.0 * std::sqrt(0.3 / n);
      EXPECT_NEAR(poisson_disk_spacing(n), spacing, 1e-6);
      double closest = 10.0;
      for (size_t i = 0; i < taps.size(); ++i) {
        EXPECT_LE(std::hypot(double(taps[i].x), double(taps[i].y)), 1.0 + 1e-6);
        if (i > 0) {
          EXPECT_GE(std::hypot(double(taps[i - 1].x), double(taps[i - 1].y)),
                    std::hypot(double(taps[i].x), double(taps[i].y)));
        }
        for (size_t j = 0; j < i; ++j)
          closest = std::min(
              closest, std::hypot(double(taps[i].x - taps[j].x), double(taps[i].y - taps[j].y)));
      }
      if (n > 1) {
        EXPECT_GE(closest, spacing * (1.0 - 1e-5));
      }
    }
}

// Same (n, seed), same taps; another seed, other taps. And the taps spread
// over the disk: each quadrant of a 32-tap disk holds some.
TEST(PoissonDisk, IsAFunctionOfCountAndSeedAndFillsTheDisk) {
  const std::vector<glm::vec2> a = poisson_disk(32, 5), b = poisson_disk(32, 5),
                               c = poisson_disk(32, 6);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  int quadrants[4] = {0, 0, 0, 0};
  for (const glm::vec2& p : a) ++quadrants[(p.x >= 0.0f ? 1 : 0) + (p.y >= 0.0f ? 2 : 0)];
  for (int q : quadrants) EXPECT_GE(q, 4);
}

}  // namespace
}  // namespace sb::techniques
