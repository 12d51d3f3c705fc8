// metrics::distance_thirds: pixels by their distance from the camera, in
// equal thirds of the measured distances' range.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "metrics/distance_thirds.h"

namespace sb::metrics {

using core::ImageF;

namespace {

// A row of pixels on the x axis at x = 1..width, seen from the origin.
ImageF row_of_points(int width) {
  ImageF p(width, 1, 4);
  for (int x = 0; x < width; ++x) {
    p.data[size_t(x) * 4 + 0] = float(x + 1);
    p.data[size_t(x) * 4 + 3] = 1.0f;
  }
  return p;
}

TEST(DistanceThirds, SplitsTheMeasuredRangeIntoEqualDistanceIntervals) {
  // Distances 1..10: the range 9 splits at 4 and 7.
  const ImageF p = row_of_points(10);
  const auto t = distance_thirds(p, glm::vec3(0.0f), std::vector<uint8_t>(10, 1));
  const std::vector<uint8_t> near = {1, 1, 1, 1, 0, 0, 0, 0, 0, 0};
  const std::vector<uint8_t> middle = {0, 0, 0, 0, 1, 1, 1, 0, 0, 0};
  const std::vector<uint8_t> far = {0, 0, 0, 0, 0, 0, 0, 1, 1, 1};
  EXPECT_EQ(t[0], near);
  EXPECT_EQ(t[1], middle);
  EXPECT_EQ(t[2], far);
}

// Distances 1, 2, 4, ..., 256 and 1024: log thirds split at the ratios
// 2^(10/3) and 2^(20/3) of the least, whatever the unit.
TEST(DistanceThirds, OnTheLogScaleSplitsAtEqualRatios) {
  for (const float unit : {1.0f, 1000.0f}) {
    ImageF p(10, 1, 4);
    for (int x = 0; x < 10; ++x) {
      p.data[size_t(x) * 4 + 0] = unit * std::ldexp(1.0f, x < 9 ? x : 10);
      p.data[size_t(x) * 4 + 3] = 1.0f;
    }
    // log2 distances 0..8 and 10: thirds end at 3.33 and 6.67.
    const auto t =
        distance_thirds(p, glm::vec3(0.0f), std::vector<uint8_t>(10, 1), DistanceScale::Log);
    EXPECT_EQ(t[0], (std::vector<uint8_t>{1, 1, 1, 1, 0, 0, 0, 0, 0, 0})) << unit;
    EXPECT_EQ(t[1], (std::vector<uint8_t>{0, 0, 0, 0, 1, 1, 1, 0, 0, 0})) << unit;
    EXPECT_EQ(t[2], (std::vector<uint8_t>{0, 0, 0, 0, 0, 0, 0, 1, 1, 1})) << unit;
    // The linear thirds of the same pixels: 1..1024 splits at 342 and 683.
    const auto linear = distance_thirds(p, glm::vec3(0.0f), std::vector<uint8_t>(10, 1));
    EXPECT_EQ(linear[0], (std::vector<uint8_t>{1, 1, 1, 1, 1, 1, 1, 1, 1, 0})) << unit;
  }
}

TEST(DistanceThirds, LeavesOutBackgroundAndUnmeasuredPixelsAndTheirDistances) {
  ImageF p = row_of_points(10);
  p.data[9 * 4 + 3] = 0.0f;  // background at distance 10
  std::vector<uint8_t> measured(10, 1);
  measured[0] = 0;  // unmeasured at distance 1
  // Measured distances 2..9: the range 7 splits at 4.33 and 6.67.
  const auto t = distance_thirds(p, glm::vec3(0.0f), measured);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(t[size_t(k)][0], 0);
    EXPECT_EQ(t[size_t(k)][9], 0);
  }
  EXPECT_EQ(t[0][3], 1);  // 4
  EXPECT_EQ(t[1][4], 1);  // 5
  EXPECT_EQ(t[1][5], 1);  // 6
  EXPECT_EQ(t[2][6], 1);  // 7
}

TEST(DistanceThirds, MeasuresFromTheEye) {
  // From x = 11, the pixel at x = 10 is the nearest.
  const auto t =
      distance_thirds(row_of_points(10), glm::vec3(11, 0, 0), std::vector<uint8_t>(10, 1));
  EXPECT_EQ(t[0][9], 1);
  EXPECT_EQ(t[2][0], 1);
}

TEST(DistanceThirds, PutsEveryPixelNearWhenAllAreAtOneDistance) {
  ImageF p(3, 1, 4);
  for (int x = 0; x < 3; ++x) {
    p.data[size_t(x) * 4 + 2] = 5.0f;
    p.data[size_t(x) * 4 + 3] = 1.0f;
  }
  const auto t = distance_thirds(p, glm::vec3(0.0f), std::vector<uint8_t>(3, 1));
  EXPECT_EQ(t[0], std::vector<uint8_t>(3, 1));
}

TEST(DistanceThirds, RejectsAMaskOfAnotherSize) {
  EXPECT_THROW(distance_thirds(row_of_points(4), glm::vec3(0.0f), std::vector<uint8_t>(3, 1)),
               std::invalid_argument);
}

}  // namespace
}  // namespace sb::metrics
