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

  // A leaf of the hierarchy, and which of its triangles a query keeps
  // (bit i: its i-th; a leaf has at most four).
  struct Leaf {
    uint32_t node;
    uint32_t triangles;
  };

  // Appends to `out` the leaves that traverse(keep, ·) would visit, in its
  // order, each with the triangles that keep_triangle(triangle) accepts
  // (none: not appended).
  template <typename Keep, typename KeepTriangle>
  void leaves(const Keep& keep, const KeepTriangle& keep_triangle, std::vector<Leaf>& out) const;

  // Calls visit(lo, hi, first, kept) for each of `leaves` (from leaves())
  // whose own box [lo, hi] keep accepts, in their order: its triangles
  // first[i] for each bit i of kept. These are the triangles that
  // traverse(keep, ·) visits, in its order, when the leaves came from
  // leaves() with tests that accept every box and triangle that keep does,
  // or at least every one holding a triangle that the visit acts on.
  template <typename Keep, typename VisitLeaf>
  void traverse_leaves(const std::vector<Leaf>& leaves, const Keep& keep,
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

template <typename Keep, typename KeepTriangle>
void CasterBvh::leaves(const Keep& keep, const KeepTriangle& keep_triangle,
                       std::vector<Leaf>& out) const {
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
      continue;
    }
    uint32_t kept = 0;
    for (uint32_t i = 0; i < node.count; ++i)
      if (keep_triangle(triangles_[node.first + i])) kept |= 1u << i;
    if (kept != 0) out.push_back({index, kept});
  }
}

template <typename Keep, typename VisitLeaf>
void CasterBvh::traverse_leaves(const std::vector<Leaf>& leaves, const Keep& keep,
                                const VisitLeaf& visit) const {
  for (const Leaf& leaf : leaves) {
    const Node& node = nodes_[leaf.node];
    if (keep(node.lo, node.hi))
      visit(node.lo, node.hi, triangles_.data() + node.first, leaf.triangles);
  }
}

}  // namespace sb::reference::detail
