#pragma once
// The exact reference's casters (exact_visibility.h): their triangles in
// double precision, with what closed_parts.h finds about them, in a
// bounding-volume hierarchy that queries walk by culling its boxes.
#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <type_traits>
#include <vector>

namespace sb::reference::detail {

inline constexpr uint32_t kNoNeighbour = 0xffffffffu;
inline constexpr uint32_t kNoPart = 0xffffffffu;

struct CasterTriangle {
  glm::dvec3 a, b, c;
  // A closed part's: +1 when its part winds outward (positive signed
  // volume), -1 inward; 0 for any other caster's.
  int outward = 0;
  uint32_t mesh = 0;        // index into the scene's meshes
  uint32_t part = kNoPart;  // its closed part (closed_parts.h), or kNoPart
  glm::dvec3 normal{0.0};   // (b - a) × (c - a)
  // A closed caster's: the triangle across edge k (a-b, b-c, c-a), or
  // kNoNeighbour where no single other triangle shares it.
  std::array<uint32_t, 3> neighbour{kNoNeighbour, kNoNeighbour, kNoNeighbour};
};

class CasterBvh {
 public:
  CasterBvh() = default;
  // Puts the triangles in the hierarchy's order (leaves of at most four,
  // split at the median centroid along the box's longest axis).
  explicit CasterBvh(std::vector<CasterTriangle> triangles);

  bool empty() const { return nodes_.empty(); }
  // In the hierarchy's order; their fields may change, not their order.
  std::vector<CasterTriangle>& triangles() { return triangles_; }
  const std::vector<CasterTriangle>& triangles() const { return triangles_; }

  // Calls visit(triangle) for the triangles of every leaf whose box, and its
  // ancestors', keep(lo, hi) accepts. A visit that returns bool stops the
  // walk by returning false, and traverse() then returns false.
  template <typename Keep, typename Visit>
  bool traverse(const Keep& keep, const Visit& visit) const;

  // Appends to `out` the leaves (as indices for traverse_leaves) that
  // traverse(keep, ·) would visit, in its order.
  template <typename Keep>
  void leaves(const Keep& keep, std::vector<uint32_t>& out) const;

  // Calls visit(lo, hi, first, last) for each of `leaves` (from leaves())
  // whose own box [lo, hi] keep accepts, in their order, its triangles
  // [first, last): the triangles that traverse(keep, ·) visits, in its
  // order, when `leaves` came from a keep that accepts every box `keep`
  // does, or at least every box holding a triangle that the visit acts on.
  template <typename Keep, typename VisitLeaf>
  void traverse_leaves(const std::vector<uint32_t>& leaves, const Keep& keep,
                       const VisitLeaf& visit) const;

 private:
  struct Node {
    glm::dvec3 lo, hi;
    uint32_t first = 0, count = 0;  // leaf: triangles [first, first + count)
    uint32_t left = 0, right = 0;   // inner: children (count == 0)
  };
  uint32_t build(uint32_t first, uint32_t count);
  template <typename Visit>
  bool visit_leaf(const Node& node, const Visit& visit) const;

  std::vector<CasterTriangle> triangles_;
  std::vector<Node> nodes_;
};

template <typename Visit>
bool CasterBvh::visit_leaf(const Node& node, const Visit& visit) const {
  for (uint32_t i = node.first; i < node.first + node.count; ++i) {
    if constexpr (std::is_void_v<std::invoke_result_t<const Visit&, const CasterTriangle&>>)
      visit(triangles_[i]);
    else if (!visit(triangles_[i]))
      return false;
  }
  return true;
}

template <typename Keep, typename Visit>
bool CasterBvh::traverse(const Keep& keep, const Visit& visit) const {
  if (nodes_.empty()) return true;
  // The median split halves every node, so the depth is at most 32 and
  // the stack, one deeper per level, never holds more than 33.
  std::array<uint32_t, 64> stack;
  size_t size = 1;
  stack[0] = 0;
  while (size > 0) {
    const Node& node = nodes_[stack[--size]];
    if (!keep(node.lo, node.hi)) continue;
    if (node.count == 0) {
      stack[size++] = node.left;
      stack[size++] = node.right;
      continue;
    }
    if (!visit_leaf(node, visit)) return false;
  }
  return true;
}

template <typename Keep>
void CasterBvh::leaves(const Keep& keep, std::vector<uint32_t>& out) const {
  if (nodes_.empty()) return;
  std::array<uint32_t, 64> stack;  // as traverse()'s
  size_t size = 1;
  stack[0] = 0;
  while (size > 0) {
    const uint32_t index = stack[--size];
    const Node& node = nodes_[index];
    if (!keep(node.lo, node.hi)) continue;
    if (node.count == 0) {
      stack[size++] = node.left;
      stack[size++] = node.right;
    } else {
      out.push_back(index);
    }
  }
}

template <typename Keep, typename VisitLeaf>
void CasterBvh::traverse_leaves(const std::vector<uint32_t>& leaves, const Keep& keep,
                                const VisitLeaf& visit) const {
  for (const uint32_t index : leaves) {
    const Node& node = nodes_[index];
    if (keep(node.lo, node.hi))
      visit(node.lo, node.hi, triangles_.data() + node.first,
            triangles_.data() + node.first + node.count);
  }
}

}  // namespace sb::reference::detail
