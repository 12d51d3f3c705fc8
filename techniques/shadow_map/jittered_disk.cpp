#include "shadow_map/jittered_disk.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/counter_rng.h"

namespace sb::techniques::shadow_map {

using core::uniform_float;

std::vector<glm::vec2> jittered_disk(int n, unsigned seed) {
  const float golden = std::numbers::pi_v<float> * (3.0f - std::sqrt(5.0f));
  std::vector<glm::vec2> points;
  for (int i = 0; i < n; ++i) {
    const float r = std::sqrt((float(i) + uniform_float(seed, uint64_t(i))) / float(n));
    const float phi = float(i) * golden;
    points.emplace_back(r * std::cos(phi), r * std::sin(phi));
  }
  std::reverse(points.begin(), points.end());
  return points;
}

}  // namespace sb::techniques::shadow_map
