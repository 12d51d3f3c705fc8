#include "scenes/point_box_tree.h"

#include <algorithm>
#include <utility>

namespace sb {
namespace {

constexpr uint32_t kLeafPoints = 16;
constexpr int kMaxDepth = 48;  // median splits: never reached below 2^48 points

// The lowest and highest value of n·p + d over the box [lo, hi].
std::pair<double, double> plane_range(const glm::dvec3& lo, const glm::dvec3& hi,
                                      const glm::dvec3& n, double d) {
  double low = d, high = d;
  for (int i = 0; i < 3; ++i) {
    const double a = n[i] * lo[i], b = n[i] * hi[i];
    low += std::min(a, b);
    high += std::max(a, b);
  }
  return {low, high};
}

}  // namespace

PointBoxTree::PointBoxTree(std::vector<glm::vec3> points) : points_(std::move(points)) {
  if (points_.empty()) return;
  nodes_.reserve(2 * (points_.size() / kLeafPoints + 1));
  nodes_.emplace_back();
  build(0, 0, uint32_t(points_.size()), 0);
}

void PointBoxTree::build(uint32_t index, uint32_t begin, uint32_t end, int depth) {
  glm::dvec3 lo(points_[begin]), hi(points_[begin]);
  for (uint32_t i = begin + 1; i < end; ++i) {
    lo = glm::min(lo, glm::dvec3(points_[i]));
    hi = glm::max(hi, glm::dvec3(points_[i]));
  }
  Node& node = nodes_[index];
  node.lo = lo;
  node.hi = hi;
  node.begin = begin;
  node.end = end;
  const glm::dvec3 extent = hi - lo;
  if (end - begin <= kLeafPoints || depth >= kMaxDepth ||
      (extent.x == 0.0 && extent.y == 0.0 && extent.z == 0.0))
    return;  // a leaf (points in one spot cannot be split)
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  const uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(points_.begin() + begin, points_.begin() + mid, points_.begin() + end,
                   [axis](const glm::vec3& a, const glm::vec3& b) { return a[axis] < b[axis]; });
  const auto left = uint32_t(nodes_.size());
  node.left = left;  // `node` may dangle after the next emplace_back
  nodes_.emplace_back();
  nodes_.emplace_back();
  build(left, begin, mid, depth + 1);
  build(left + 1, mid, end, depth + 1);
}

bool PointBoxTree::any_below(const glm::dvec3& n, double d, double depth) const {
  if (nodes_.empty()) return false;
  std::vector<uint32_t> stack = {0};
  while (!stack.empty()) {
    const Node& node = nodes_[stack.back()];
    stack.pop_back();
    const auto [low, high] = plane_range(node.lo, node.hi, n, d);
    if (low >= -depth) continue;     // every point of the box is above
    if (high < -depth) return true;  // every point is below, and the box holds one
    if (node.left == 0) {
      for (uint32_t i = node.begin; i < node.end; ++i)
        if (glm::dot(n, glm::dvec3(points_[i])) + d < -depth) return true;
      continue;
    }
    stack.push_back(node.left);
    stack.push_back(node.left + 1);
  }
  return false;
}

}  // namespace sb
