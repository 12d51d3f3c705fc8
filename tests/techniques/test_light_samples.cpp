// Accumulation's light points must cover the light in both directions for
// every sample count, primes included (a prime used to give 1×N strata: N
// thin columns, each point anywhere along its column's height).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "accumulation/light_samples.h"
#include "splitmix64_sequence.h"

namespace sb::techniques::accumulation {
namespace {

// Star discrepancy by brute force: the largest |share of points in [0,a)×[0,b)
// − a·b| over anchored boxes, whose sup is reached with a and b at point
// coordinates or 1, the box taken open or closed there.
double star_discrepancy(const std::vector<glm::vec2>& p) {
  std::vector<double> xs{1.0}, ys{1.0};
  for (const auto& q : p) {
    xs.push_back(q.x);
    ys.push_back(q.y);
  }
  const double n = double(p.size());
  double worst = 0.0;
  for (const double a : xs)
    for (const double b : ys) {
      int open = 0, closed = 0;
      for (const auto& q : p) {
        open += double(q.x) < a && double(q.y) < b;
        closed += double(q.x) <= a && double(q.y) <= b;
      }
      worst = std::max({worst, a * b - open / n, closed / n - a * b});
    }
  return worst;
}

// Points per cell of a k×k grid.
std::vector<int> cell_counts(const std::vector<glm::vec2>& p, int k) {
  std::vector<int> counts(size_t(k * k), 0);
  for (const auto& q : p) {
    const int i = std::min(int(q.x * float(k)), k - 1), j = std::min(int(q.y * float(k)), k - 1);
    ++counts[size_t(j) * size_t(k) + size_t(i)];
  }
  return counts;
}

// The Hammersley set's O(log N / N): an anchored box [0,a)×[0,b) holds the
// first ~a·N points of the van der Corput sequence below b, whose first n
// points have n·D* <= log2(n)/3 + 1 (Béjian & Faure 1977); rounding a·N and
// the half-step centring of both coordinates add at most 1.5 points. A
// toroidal shift cuts the box into up to four pieces of the unshifted set:
// shifted sets are allowed twice the bound (an allowance, not a theorem).
// The 1×N layout misses it by far: its t are all ½ (D* >= ½) or independent
// uniforms (D* ~ 0.8/√N).
double discrepancy_bound(int n, bool shifted) {
  const double b = (std::log2(double(n)) / 3.0 + 2.5) / double(n);
  return shifted ? 2.0 * b : b;
}

constexpr int kPrimes[] = {7, 13, 31, 127, 257};

TEST(LightSamples, EveryPointIsOnTheLight) {
  for (int n : {1, 2, 3, 7, 13, 16, 22, 127, 128, 256, 257})
    for (bool jitter : {false, true}) {
      const auto p = light_samples(n, jitter, 3);
      ASSERT_EQ(p.size(), size_t(n));
      for (const auto& q : p) {
        EXPECT_TRUE(q.x >= 0.0f && q.x < 1.0f && q.y >= 0.0f && q.y < 1.0f)
            << n << ": " << q.x << "," << q.y;
      }
    }
}

TEST(LightSamples, PrimeCountsHaveLowStarDiscrepancy) {
  for (int n : kPrimes) {
    const double plain = star_discrepancy(light_samples(n, false, 1));
    EXPECT_LE(plain, discrepancy_bound(n, false)) << "N = " << n;
    RecordProperty("dstar_" + std::to_string(n), std::to_string(plain));
    double worst = 0.0;
    for (unsigned seed = 1; seed <= 8; ++seed) {
      const double d = star_discrepancy(light_samples(n, true, seed));
      worst = std::max(worst, d);
      EXPECT_LE(d, discrepancy_bound(n, true)) << "N = " << n << ", seed " << seed;
    }
    RecordProperty("dstar_jittered_worst_" + std::to_string(n), std::to_string(worst));
  }
}

// Cells of a ⌈√N⌉ grid hold about one point each: at most four (a stratum
// of an m×2m grid can straddle two cells each way), never a column's worth.
TEST(LightSamples, NoCellOfASquareGridIsCrowded) {
  for (int n : {2, 3, 5, 7, 8, 13, 22, 31, 32, 127, 128, 257})
    for (bool jitter : {false, true})
      for (unsigned seed = 1; seed <= (jitter ? 8u : 1u); ++seed) {
        const int k = int(std::ceil(std::sqrt(double(n))));
        const auto counts = cell_counts(light_samples(n, jitter, seed), k);
        EXPECT_LE(*std::max_element(counts.begin(), counts.end()), 4)
            << "N = " << n << (jitter ? ", jittered, seed " : ", plain, seed ") << seed;
      }
}

// Square counts are the n×n grid of strata: one point in each cell, at its
// centre unless jittered.
TEST(LightSamples, SquareCountsAreOnePointPerCell) {
  for (int k : {1, 2, 4, 8, 16}) {
    const int n = k * k;
    for (bool jitter : {false, true}) {
      const auto p = light_samples(n, jitter, 5);
      const auto counts = cell_counts(p, k);
      EXPECT_TRUE(std::all_of(counts.begin(), counts.end(), [](int c) { return c == 1; }))
          << "N = " << n;
      if (jitter) continue;
      for (const auto& q : p) {
        const float cx = (std::floor(q.x * float(k)) + 0.5f) / float(k);
        const float cy = (std::floor(q.y * float(k)) + 0.5f) / float(k);
        EXPECT_FLOAT_EQ(q.x, cx);
        EXPECT_FLOAT_EQ(q.y, cy);
      }
    }
  }
}

TEST(LightSamples, SameSeedSamePointsOtherSeedOtherPoints) {
  for (int n : {13, 16}) {
    const auto a = light_samples(n, true, 9), b = light_samples(n, true, 9),
               c = light_samples(n, true, 10);
    EXPECT_EQ(a, b);
    EXPECT_NE(a, c);
  }
}

// On a segment the square's t collapses (an m×n grid would leave n distinct
// strata along it): a segment gets one point in each of N strata of its own.
TEST(LightSamples, ASegmentGetsOnePointInEachOfNStrata) {
  for (const int n : {1, 2, 7, 16, 64, 256, 257}) {
    for (const bool jitter : {false, true}) {
      const std::vector<float> s = segment_samples(n, jitter, 3);
      ASSERT_EQ(s.size(), size_t(n));
      std::vector<int> per_stratum(size_t(n), 0);
      for (const float x : s) {
        ASSERT_GE(x, 0.0f);
        ASSERT_LT(x, 1.0f);
        ++per_stratum[size_t(std::min(int(x * float(n)), n - 1))];
        if (!jitter) {
          const float centre = (std::floor(x * float(n)) + 0.5f) / float(n);
          EXPECT_NEAR(x, centre, 1e-6f);
        }
      }
      for (const int c : per_stratum) EXPECT_EQ(c, 1) << n << (jitter ? " jittered" : "");
    }
  }
  EXPECT_EQ(segment_samples(64, true, 3), segment_samples(64, true, 3));
  EXPECT_NE(segment_samples(64, true, 3), segment_samples(64, true, 4));
  const LightSampleLayouts both = light_sample_layouts(16, true, 3);
  EXPECT_EQ(both.square, light_samples(16, true, 3));
  EXPECT_EQ(both.line, segment_samples(16, true, 3));
}

// The jitter is the documented function of (seed, index) (light_samples.h):
// uniform j of the seed's SplitMix64 stream, whatever the standard library.
// Grid stratum k takes j = 2k (s) and 2k + 1 (t); the Hammersley shift
// j = 0 and 1; a segment's stratum i takes j = i.
TEST(LightSamples, JitterIsTheDocumentedFunctionOfSeedAndIndex) {
  for (const unsigned seed : {1u, 7u, 2147483647u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const std::vector<float> u = sbtest::splitmix64_uniforms(seed, 2 * 24);
    // 24 = 4×6: the grid, rows of 6.
    const auto grid = light_samples(24, true, seed);
    for (int k = 0; k < 24; ++k) {
      const int r = k / 6, c = k % 6;
      EXPECT_EQ(grid[size_t(k)].x, (float(c) + u[size_t(2 * k)]) / 6.0f) << "stratum " << k;
      EXPECT_EQ(grid[size_t(k)].y, (float(r) + u[size_t(2 * k + 1)]) / 4.0f) << "stratum " << k;
    }
    // 13 (prime): the Hammersley set shifted by (u_0, u_1), mod 1.
    const auto hammersley = light_samples(13, true, seed);
    for (int i = 0; i < 13; ++i) {
      double radical = 0.0, digit = 0.5;
      for (int b = i; b > 0; b /= 2, digit /= 2) radical += (b % 2) * digit;
      const double s = (i + 0.5) / 13.0 + double(u[0]);
      const double t = radical + 0.5 / 16.0 + double(u[1]);
      EXPECT_FLOAT_EQ(hammersley[size_t(i)].x, float(s - std::floor(s))) << "point " << i;
      EXPECT_FLOAT_EQ(hammersley[size_t(i)].y, float(t - std::floor(t))) << "point " << i;
    }
    const std::vector<float> segment = segment_samples(16, true, seed);
    for (int i = 0; i < 16; ++i)
      EXPECT_EQ(segment[size_t(i)], float((double(i) + double(u[size_t(i)])) / 16.0))
          << "stratum " << i;
  }
}

}  // namespace
}  // namespace sb::techniques::accumulation
