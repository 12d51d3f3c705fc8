#include "reference/caster_bvh.h"

#include <algorithm>

namespace sb::reference::detail {

CasterBvh::CasterBvh(std::vector<CasterTriangle> triangles) : triangles_(std::move(triangles)) {
  if (!triangles_.empty()) build(0, uint32_t(triangles_.size()));
}

uint32_t CasterBvh::build(uint32_t first, uint32_t count) {
  Node node;
  node.lo = glm::dvec3(1e300);
  node.hi = glm::dvec3(-1e300);
  for (uint32_t i = first; i < first + count; ++i)
    for (const glm::dvec3& x : {triangles_[i].a, triangles_[i].b, triangles_[i].c}) {
      node.lo = glm::min(node.lo, x);
      node.hi = glm::max(node.hi, x);
    }
  const auto index = uint32_t(nodes_.size());
  nodes_.push_back(node);
  if (count <= 4) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  const glm::dvec3 extent = node.hi - node.lo;
  const int axis =
      extent.x > extent.y ? (extent.x > extent.z ? 0 : 2) : (extent.y > extent.z ? 1 : 2);
  const auto centroid = [axis](const CasterTriangle& t) {
    return t.a[axis] + t.b[axis] + t.c[axis];
  };
  const uint32_t half = count / 2;
  std::nth_element(
      triangles_.begin() + first, triangles_.begin() + first + half,
      triangles_.begin() + first + count,
      [&](const CasterTriangle& x, const CasterTriangle& y) { return centroid(x) < centroid(y); });
  const uint32_t left = build(first, half);
  const uint32_t right = build(first + half, count - half);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

}  // namespace sb::reference::detail
