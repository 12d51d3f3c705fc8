#include "raytraced/shadow_bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"

namespace sb::techniques::raytraced {

namespace {

constexpr int kBins = 16;
// SAH costs of a node visit and a triangle test (the usual 1 : 1 ratio of a
// shadow ray whose test is about as dear as a box's).
constexpr float kTraversalCost = 1.0f;
constexpr float kTriangleCost = 1.0f;

struct Box {
  glm::vec3 lo{std::numeric_limits<float>::max()};
  glm::vec3 hi{-std::numeric_limits<float>::max()};
  void extend(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void extend(const Box& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  bool empty() const { return lo.x > hi.x; }
  float area() const {
    if (empty()) return 0.0f;
    const glm::vec3 e = hi - lo;
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
};

struct Builder {
  const std::vector<BvhTriangle>& tris;
  int leaf_size;
  std::vector<Box> bounds;
  std::vector<glm::vec3> centroids;
  ShadowBvh out;

  uint32_t build(uint32_t first, uint32_t count, int depth) {
    if (depth > kMaxBvhDepth)
      throw core::JobError("raytraced: the hierarchy grew deeper than " +
                           std::to_string(kMaxBvhDepth) + " levels");
    out.depth = std::max(out.depth, depth);
    const auto index = uint32_t(out.nodes.size());
    out.nodes.emplace_back();
    Box box, centre;
    for (uint32_t k = first; k < first + count; ++k) {
      box.extend(bounds[out.order[k]]);
      centre.extend(centroids[out.order[k]]);
    }
    out.nodes[index].lo = box.lo;
    out.nodes[index].hi = box.hi;

    // The best binned split over the three axes.
    int best_axis = -1, best_bin = 0;
    float best_cost = std::numeric_limits<float>::max();
    for (int axis = 0; axis < 3; ++axis) {
      const float lo = centre.lo[axis], extent = centre.hi[axis] - lo;
      if (!(extent > 0.0f)) continue;
      std::array<Box, kBins> bin_box;
      std::array<uint32_t, kBins> bin_count{};
      const float scale = float(kBins) / extent;
      for (uint32_t k = first; k < first + count; ++k) {
        const uint32_t t = out.order[k];
        const int b = std::min(kBins - 1, int((centroids[t][axis] - lo) * scale));
        bin_box[size_t(b)].extend(bounds[t]);
        ++bin_count[size_t(b)];
      }
      // Sweeps from the right, then from the left: the cost of splitting
      // after bin b (left = bins 0..b).
      std::array<float, kBins> right_cost{};
      Box acc;
      uint32_t n = 0;
      for (int b = kBins - 1; b > 0; --b) {
        acc.extend(bin_box[size_t(b)]);
        n += bin_count[size_t(b)];
        right_cost[size_t(b - 1)] = acc.area() * float(n);
      }
      acc = Box{};
      n = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        acc.extend(bin_box[size_t(b)]);
        n += bin_count[size_t(b)];
        if (n == 0 || n == count) continue;
        const float cost = acc.area() * float(n) + right_cost[size_t(b)];
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_bin = b;
        }
      }
    }
    const float area = box.area();
    const float split_cost =
        best_axis < 0 ? std::numeric_limits<float>::max()
                      : kTraversalCost + kTriangleCost * best_cost / std::max(area, 1e-30f);
    const bool small = count <= uint32_t(leaf_size);
    if (count == 1 || (small && kTriangleCost * float(count) <= split_cost)) {
      out.nodes[index].first = first;
      out.nodes[index].count = count;
      return index;
    }
    uint32_t mid = 0;
    if (best_axis >= 0) {
      const float lo = centre.lo[best_axis];
      const float scale = float(kBins) / (centre.hi[best_axis] - lo);
      const auto split = std::partition(
          out.order.begin() + first, out.order.begin() + first + count, [&](uint32_t t) {
            return std::min(kBins - 1, int((centroids[t][best_axis] - lo) * scale)) <= best_bin;
          });
      mid = uint32_t(split - out.order.begin()) - first;
    }
    if (mid == 0 || mid == count) mid = count / 2;  // every centroid in one place
    build(first, mid, depth + 1);
    const uint32_t right = build(first + mid, count - mid, depth + 1);
    out.nodes[index].right = right;
    return index;
  }
};

float max_abs_axis(const glm::vec3& d, int& kz) {
  const glm::vec3 a = glm::abs(d);
  kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  return a[kz];
}

}  // namespace

ShadowBvh build_shadow_bvh(const std::vector<BvhTriangle>& triangles, int leaf_size) {
  Builder b{triangles, std::max(1, leaf_size), {}, {}, {}};
  if (triangles.empty()) return {};
  b.bounds.resize(triangles.size());
  b.centroids.resize(triangles.size());
  b.out.order.resize(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i) {
    const BvhTriangle& t = triangles[i];
    b.bounds[i].extend(t.a);
    b.bounds[i].extend(t.b);
    b.bounds[i].extend(t.c);
    b.centroids[i] = (t.a + t.b + t.c) / 3.0f;
    b.out.order[i] = uint32_t(i);
  }
  b.out.nodes.reserve(2 * triangles.size());
  b.build(0, uint32_t(triangles.size()), 0);
  std::vector<BvhNode>& nodes = b.out.nodes;
  for (size_t i = nodes.size(); i-- > 0;)
    nodes[i].skip = nodes[i].leaf() ? uint32_t(i) + 1 : nodes[nodes[i].right].skip;
  return std::move(b.out);
}

float ray_triangle(const glm::vec3& origin, const glm::vec3& dir, const BvhTriangle& tri,
                   glm::vec3& weights) {
  // Woop, Benthin & Wald 2013, as pbrt-v3 writes it: the ray becomes the +z
  // axis by a translation, a permutation and a shear, and the edge functions
  // of the sheared corners decide; edge functions of exactly 0 are redone in
  // double so that the decision along a shared edge is the same for both
  // triangles.
  int kz = 0;
  max_abs_axis(dir, kz);
  const int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  const glm::vec3 d(dir[kx], dir[ky], dir[kz]);
  glm::vec3 p0 = tri.a - origin, p1 = tri.b - origin, p2 = tri.c - origin;
  p0 = {p0[kx], p0[ky], p0[kz]};
  p1 = {p1[kx], p1[ky], p1[kz]};
  p2 = {p2[kx], p2[ky], p2[kz]};
  const float sx = -d.x / d.z, sy = -d.y / d.z, sz = 1.0f / d.z;
  p0.x += sx * p0.z;
  p0.y += sy * p0.z;
  p1.x += sx * p1.z;
  p1.y += sy * p1.z;
  p2.x += sx * p2.z;
  p2.y += sy * p2.z;
  float e0 = p1.x * p2.y - p1.y * p2.x;
  float e1 = p2.x * p0.y - p2.y * p0.x;
  float e2 = p0.x * p1.y - p0.y * p1.x;
  if (e0 == 0.0f || e1 == 0.0f || e2 == 0.0f) {
    e0 = float(double(p1.x) * double(p2.y) - double(p1.y) * double(p2.x));
    e1 = float(double(p2.x) * double(p0.y) - double(p2.y) * double(p0.x));
    e2 = float(double(p0.x) * double(p1.y) - double(p0.y) * double(p1.x));
  }
  if ((e0 < 0.0f || e1 < 0.0f || e2 < 0.0f) && (e0 > 0.0f || e1 > 0.0f || e2 > 0.0f)) return -1.0f;
  const float det = e0 + e1 + e2;
  if (det == 0.0f) return -1.0f;
  const float t_scaled = e0 * (p0.z * sz) + e1 * (p1.z * sz) + e2 * (p2.z * sz);
  const float inv = 1.0f / det;
  weights = glm::vec3(e0, e1, e2) * inv;
  return t_scaled * inv;
}

glm::vec3 safe_inverse(const glm::vec3& d) {
  glm::vec3 inv;
  for (int k = 0; k < 3; ++k) {
    const float c = std::fabs(d[k]) < 1e-30f ? std::copysign(1e-30f, d[k]) : d[k];
    inv[k] = 1.0f / c;
  }
  return inv;
}

bool ray_box(const glm::vec3& origin, const glm::vec3& inv_dir, const glm::vec3& lo,
             const glm::vec3& hi, float tfar) {
  const glm::vec3 t0 = (lo - origin) * inv_dir, t1 = (hi - origin) * inv_dir;
  const glm::vec3 tmin = glm::min(t0, t1), tmax = glm::max(t0, t1);
  const float enter = std::max({tmin.x, tmin.y, tmin.z, 0.0f});
  // 1 + 2γ(3) of Ize 2013, rounded up.
  const float leave = std::min({tmax.x, tmax.y, tmax.z, tfar}) * 1.0000004f;
  return enter <= leave;
}

}  // namespace sb::techniques::raytraced
