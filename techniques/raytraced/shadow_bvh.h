#pragma once
// raytraced's bounding-volume hierarchy over the caster triangles, built on
// the CPU once per scene (prepare(): it depends on the static geometry only)
// with the binned surface-area heuristic (Wald 2007, "On fast construction
// of SAH-based bounding volume hierarchies"), and the any-hit query the GPU
// runs, here on the CPU too so that tests can hold the two to brute force.
//
//   in     triangles (three float corners each), leaf_size (most triangles
//          per leaf, 1..64);
//   out    nodes in depth-first order: an inner node's left child is the
//          next node, its right child `right`; a leaf's triangles are
//          order[first .. first + count) (indices into the input); every
//          node's `skip` the node after its subtree, so a walk needs no
//          stack: into a node whose box it enters (the next node), past it
//          (skip) when it misses;
//   cost   O(n log n): 16 bins per axis and node.
//
// The ray-triangle test is watertight (Woop, Benthin & Wald 2013): a ray
// through an edge two triangles share hits one of them, as the reference's
// Embree does in its robust mode; both faces count (no culling).
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace sb::techniques::raytraced {

struct BvhTriangle {
  glm::vec3 a, b, c;
};

struct BvhNode {
  glm::vec3 lo{0.0f}, hi{0.0f};
  uint32_t first = 0;  // leaf: first entry of `order`; inner: unused
  uint32_t count = 0;  // leaf: triangles (> 0); inner: 0
  uint32_t right = 0;  // inner: the right child (the left one is the next node)
  uint32_t skip = 0;   // the node after this one's subtree (nodes.size() after the root's)
  bool leaf() const { return count > 0; }
};

struct ShadowBvh {
  std::vector<BvhNode> nodes;  // empty without triangles
  std::vector<uint32_t> order;
  int depth = 0;  // of the deepest leaf, the root's 0
};

// Most levels build() makes (it recurses once a level): it throws JobError
// past it.
inline constexpr int kMaxBvhDepth = 60;

ShadowBvh build_shadow_bvh(const std::vector<BvhTriangle>& triangles, int leaf_size);

// The hit distance t of the watertight test, or a negative number for a miss;
// also the barycentric weights of a, b and c at the hit.
float ray_triangle(const glm::vec3& origin, const glm::vec3& dir, const BvhTriangle& tri,
                   glm::vec3& weights);

// Does the ray origin + t·dir, 0 < t <= tfar, hit a triangle that `opaque`
// (index, barycentric weights) accepts? Stops at the first.
template <typename Opaque>
bool occluded(const ShadowBvh& bvh, const std::vector<BvhTriangle>& triangles,
              const glm::vec3& origin, const glm::vec3& dir, float tfar, const Opaque& opaque);

// The slab test the traversal uses: the interval of the ray inside the box,
// widened by a few ulps so that rounding never culls a box whose triangle
// the watertight test hits (Ize 2013, "Robust BVH ray traversal").
bool ray_box(const glm::vec3& origin, const glm::vec3& inv_dir, const glm::vec3& lo,
             const glm::vec3& hi, float tfar);

// 1/d per component, a zero component replaced by a tiny one of its sign
// (so that the slab test never multiplies 0 by infinity).
glm::vec3 safe_inverse(const glm::vec3& d);

template <typename Opaque>
bool occluded(const ShadowBvh& bvh, const std::vector<BvhTriangle>& triangles,
              const glm::vec3& origin, const glm::vec3& dir, float tfar, const Opaque& opaque) {
  if (bvh.nodes.empty()) return false;
  const glm::vec3 inv = safe_inverse(dir);
  // The shader's stackless walk (raytraced_glsl.h).
  for (uint32_t i = 0; i < bvh.nodes.size();) {
    const BvhNode& n = bvh.nodes[i];
    if (!ray_box(origin, inv, n.lo, n.hi, tfar)) {
      i = n.skip;
      continue;
    }
    for (uint32_t k = n.first; k < n.first + n.count; ++k) {
      const uint32_t t = bvh.order[k];
      glm::vec3 w;
      const float d = ray_triangle(origin, dir, triangles[t], w);
      if (d > 0.0f && d <= tfar && opaque(t, w)) return true;
    }
    ++i;
  }
  return false;
}

}  // namespace sb::techniques::raytraced
