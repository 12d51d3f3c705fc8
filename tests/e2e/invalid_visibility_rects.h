#pragma once
// Where tests/e2e/invalid_visibility_plugin.cpp writes which value of V, for
// the plugin and for the test that checks the mask of the offending pixels
// (tests/e2e/test_failed_jobs.cpp). Rectangles in GL window coordinates (y
// up) of a frame at least 40x30; they do not overlap.
#include <array>
#include <limits>

namespace sb::test {

struct InvalidRect {
  int x, y, w, h;
  float value;
};

inline constexpr std::array<InvalidRect, 5> kInvalidRects{{
    {0, 0, 8, 6, std::numeric_limits<float>::quiet_NaN()},  // 48 px NaN
    {8, 0, 4, 6, std::numeric_limits<float>::infinity()},   // 24 px +inf
    {20, 10, 5, 4, -0.25f},                                 // 20 px below 0
    {30, 20, 3, 7, 1.5f},                                   // 21 px above 1
    {34, 0, 6, 30, 1.000005f},                              // within the tolerance: valid
}};

}  // namespace sb::test
