#include "metrics/distance_thirds.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sb::metrics {

using core::ImageF;

const char* to_string(DistanceScale scale) {
  return scale == DistanceScale::Log ? "log" : "linear";
}

std::array<std::vector<uint8_t>, 3> distance_thirds(const ImageF& positions, const glm::vec3& eye,
                                                    const std::vector<uint8_t>& measured,
                                                    DistanceScale scale) {
  const size_t n = size_t(positions.width) * size_t(positions.height);
  if (positions.channels != 4 || measured.size() != n)
    throw std::invalid_argument("distance_thirds: expected RGBA positions and one mask byte each");
  std::vector<float> distance(n, 0.0f);
  std::vector<uint8_t> counted(n, 0);
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  for (size_t i = 0; i < n; ++i) {
    const float* p = &positions.data[i * 4];
    if (!measured[i] || p[3] == 0.0f) continue;
    counted[i] = 1;
    distance[i] = glm::length(glm::vec3(p[0], p[1], p[2]) - eye);
    // Equal ratios of distance: thirds split at lo·(hi/lo)^(1/3) and ^(2/3),
    // whatever the unit. (A pixel at the eye itself, never seen past a near
    // plane, would count as the least positive float.)
    if (scale == DistanceScale::Log)
      distance[i] = std::log(std::max(distance[i], std::numeric_limits<float>::min()));
    lo = std::min(lo, distance[i]);
    hi = std::max(hi, distance[i]);
  }
  std::array<std::vector<uint8_t>, 3> thirds;
  for (auto& t : thirds) t.assign(n, 0);
  const float third = (hi - lo) / 3.0f;
  for (size_t i = 0; i < n; ++i) {
    if (!counted[i]) continue;
    const int k = distance[i] <= lo + third ? 0 : distance[i] <= lo + 2.0f * third ? 1 : 2;
    thirds[size_t(k)][i] = 1;
  }
  return thirds;
}

}  // namespace sb::metrics
