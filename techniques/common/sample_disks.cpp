#include "common/sample_disks.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/counter_rng.h"

namespace sb::techniques {

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

float poisson_disk_spacing(int n) { return 2.0f * std::sqrt(0.3f / float(std::max(n, 1))); }

std::vector<glm::vec2> poisson_disk(int n, unsigned seed) {
  std::vector<glm::vec2> points;
  float spacing = poisson_disk_spacing(n);
  uint64_t dart = 0;
  int darts_at_this_spacing = 0;
  while (int(points.size()) < n) {
    if (darts_at_this_spacing == 1000 * n) {
      spacing *= 0.9f;
      darts_at_this_spacing = 0;
    }
    const float r = std::sqrt(uniform_float(seed, 2 * dart));
    const float phi = 2.0f * std::numbers::pi_v<float> * uniform_float(seed, 2 * dart + 1);
    ++dart;
    ++darts_at_this_spacing;
    const glm::vec2 p(r * std::cos(phi), r * std::sin(phi));
    const bool far_enough = std::all_of(points.begin(), points.end(), [&](const glm::vec2& q) {
      const float dx = p.x - q.x, dy = p.y - q.y;
      return dx * dx + dy * dy >= spacing * spacing;
    });
    if (far_enough) points.push_back(p);
  }
  std::stable_sort(points.begin(), points.end(), [](const glm::vec2& a, const glm::vec2& b) {
    return a.x * a.x + a.y * a.y > b.x * b.x + b.y * b.y;
  });
  return points;
}

}  // namespace sb::techniques
