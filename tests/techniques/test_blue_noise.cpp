// The kit's blue-noise mask (common/blue_noise.h): every rank once, the
// same tile for the same seed, and blue: almost no power at low spatial
// frequencies, where a white-noise permutation has its share.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "common/blue_noise.h"
#include "core/counter_rng.h"

namespace sb::techniques {
namespace {

// Mean power of the tile's DFT at 0 < |f| <= side/8 (cycles per tile),
// over the mean power at every nonzero frequency (Parseval).
double low_frequency_share(const std::vector<float>& v, int side) {
  const int n = side * side;
  double mean = 0.0;
  for (float x : v) mean += x;
  mean /= n;
  double total = 0.0;
  for (float x : v) total += (x - mean) * (x - mean);
  const double mean_power = total * n / (n - 1);
  double low = 0.0;
  int count = 0;
  const int limit = side / 8;
  for (int fy = -limit; fy <= limit; ++fy)
    for (int fx = -limit; fx <= limit; ++fx) {
      if ((fx == 0 && fy == 0) || fx * fx + fy * fy > limit * limit) continue;
      std::complex<double> sum = 0.0;
      for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
          sum += (double(v[size_t(y) * size_t(side) + size_t(x)]) - mean) *
                 std::polar(1.0, -2.0 * std::numbers::pi * (fx * x + fy * y) / side);
      low += std::norm(sum);
      ++count;
    }
  return low / count / mean_power;
}

TEST(BlueNoise, EveryRankOnceSameTileForSameSeed) {
  for (const int side : {4, 16, 64}) {
    std::vector<float> mask = blue_noise_mask(side, 3);
    EXPECT_EQ(mask, blue_noise_mask(side, 3));
    const int n = side * side;
    std::sort(mask.begin(), mask.end());
    for (int k = 0; k < n; ++k) EXPECT_FLOAT_EQ(mask[size_t(k)], (float(k) + 0.5f) / float(n));
  }
  EXPECT_NE(blue_noise_mask(16, 3), blue_noise_mask(16, 4));
  EXPECT_THROW(blue_noise_mask(24, 1), std::logic_error);
}

// White noise spreads its power evenly (share ~1); the mask keeps under a
// tenth of it below side/8 cycles per tile.
TEST(BlueNoise, HasLittlePowerAtLowFrequencies) {
  const int side = 64;
  const std::vector<float> blue = blue_noise_mask(side, 1);
  std::vector<float> white(blue.size());
  for (size_t i = 0; i < white.size(); ++i) white[i] = core::uniform_float(7, i);
  const double blue_share = low_frequency_share(blue, side);
  const double white_share = low_frequency_share(white, side);
  RecordProperty("blue_low_frequency_share", std::to_string(blue_share));
  RecordProperty("white_low_frequency_share", std::to_string(white_share));
  EXPECT_GT(white_share, 0.5);
  EXPECT_LT(blue_share, 0.1);
}

}  // namespace
}  // namespace sb::techniques
