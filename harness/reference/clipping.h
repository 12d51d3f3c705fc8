#pragma once
// Convex clipping and intersection tests in double precision, for the exact
// reference (exact_visibility.h): polygons and segments against planes,
// boxes against planes and segments, segments against triangles. Inline:
// they run per candidate triangle per pixel.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <glm/glm.hpp>
#include <initializer_list>
#include <limits>
#include <utility>
#include <vector>

namespace sb::reference::detail {

using Polygon3 = std::vector<glm::dvec3>;

struct Plane {
  glm::dvec3 normal;  // inside: dot(normal, x - point) >= 0
  glm::dvec3 point;
  double distance(const glm::dvec3& x) const { return glm::dot(normal, x - point); }
};

// Sutherland–Hodgman against one plane, keeping the inside: the n corners
// of `in` to `out` (room for 2n), returning how many it keeps.
inline size_t clip_into(const glm::dvec3* in, size_t n, const Plane& plane, glm::dvec3* out) {
  size_t m = 0;
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec3& a = in[i];
    const glm::dvec3& b = in[(i + 1) % n];
    const double da = plane.distance(a), db = plane.distance(b);
    if (da >= 0.0) out[m++] = a;
    if ((da >= 0.0) != (db >= 0.0)) out[m++] = a + (b - a) * (da / (da - db));
  }
  return m;
}

inline Polygon3 clip(const Polygon3& in, const Plane& plane) {
  Polygon3 out(2 * in.size());
  out.resize(clip_into(in.data(), in.size(), plane, out.data()));
  return out;
}

// Whether any part of triangle abc lies inside all N planes: clipped on
// fixed buffers (a convex polygon gains at most one corner a plane, so
// 3 + N at most), after the cheap answers (all inside; all outside one
// plane).
template <size_t N>
bool triangle_meets(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                    const std::array<Plane, N>& planes) {
  static_assert(N <= 13, "the buffers hold 16 corners");
  bool all_inside = true;
  for (const Plane& plane : planes) {
    const double da = plane.distance(a), db = plane.distance(b), dc = plane.distance(c);
    if (da < 0.0 && db < 0.0 && dc < 0.0) return false;
    all_inside = all_inside && da >= 0.0 && db >= 0.0 && dc >= 0.0;
  }
  if (all_inside) return true;
  std::array<glm::dvec3, 16> in{a, b, c}, out{};
  size_t n = 3;
  for (const Plane& plane : planes) {
    n = clip_into(in.data(), n, plane, out.data());
    if (n == 0) return false;
    std::swap(in, out);
  }
  return true;
}

// Whether any part of segment pq lies inside all N planes (parametric
// clipping: the part left is t in [t0, t1]).
template <std::size_t N>
bool segment_meets(const glm::dvec3& p, const glm::dvec3& q, const std::array<Plane, N>& planes) {
  double t0 = 0.0, t1 = 1.0;
  for (const Plane& plane : planes) {
    const double dp = plane.distance(p), dq = plane.distance(q);
    if (dp < 0.0 && dq < 0.0) return false;
    if (dp < 0.0) t0 = std::max(t0, dp / (dp - dq));
    if (dq < 0.0) t1 = std::min(t1, dp / (dp - dq));
    if (t0 > t1) return false;
  }
  return true;
}

// The part [t0, t1] of the segment x0 → x1 inside every plane; t0 > t1 when
// none is.
inline glm::dvec2 clip_segment(const glm::dvec3& x0, const glm::dvec3& x1,
                               std::initializer_list<const Plane*> planes) {
  glm::dvec2 t(0.0, 1.0);
  for (const Plane* plane : planes) {
    const double e0 = plane->distance(x0), e1 = plane->distance(x1);
    if (e0 < 0.0 && e1 < 0.0) return {1.0, 0.0};
    if (e0 < 0.0) t.x = std::max(t.x, e0 / (e0 - e1));
    if (e1 < 0.0) t.y = std::min(t.y, e0 / (e0 - e1));
  }
  return t;
}

// The interval of s ∈ [0, 1] where h0 + s·(h1 − h0) < 0: a segment's part
// below a plane, given its ends' signed distances.
inline bool below(double h0, double h1, glm::dvec2& interval) {
  if (h0 < 0.0 && h1 < 0.0) {
    interval = {0.0, 1.0};
  } else if (h0 < 0.0) {
    interval = {0.0, h0 / (h0 - h1)};
  } else if (h1 < 0.0) {
    interval = {h0 / (h0 - h1), 1.0};
  } else {
    return false;
  }
  return true;
}

// Where the segment o + s·d, s in (0, 1], crosses triangle abc (Möller and
// Trumbore 1997): s, or +inf when it does not.
inline double segment_crossing(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a,
                               const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 e1 = b - a, e2 = c - a;
  const glm::dvec3 q = glm::cross(d, e2);
  const double det = glm::dot(e1, q);
  if (det == 0.0) return std::numeric_limits<double>::infinity();
  const double inv = 1.0 / det;
  const glm::dvec3 r = o - a;
  const double u = glm::dot(r, q) * inv;
  if (u < 0.0 || u > 1.0) return std::numeric_limits<double>::infinity();
  const glm::dvec3 w = glm::cross(r, e1);
  const double v = glm::dot(d, w) * inv;
  if (v < 0.0 || u + v > 1.0) return std::numeric_limits<double>::infinity();
  const double s = glm::dot(e2, w) * inv;
  return s > 0.0 && s <= 1.0 ? s : std::numeric_limits<double>::infinity();
}

inline bool box_outside(const glm::dvec3& lo, const glm::dvec3& hi, const Plane& plane) {
  const glm::dvec3 far(plane.normal.x >= 0.0 ? hi.x : lo.x, plane.normal.y >= 0.0 ? hi.y : lo.y,
                       plane.normal.z >= 0.0 ? hi.z : lo.z);
  return plane.distance(far) < 0.0;
}

// Whether the box may meet the pyramid: it is outside none of its planes.
inline bool box_meets(const glm::dvec3& lo, const glm::dvec3& hi,
                      const std::array<Plane, 5>& planes) {
  for (const Plane& plane : planes)
    if (box_outside(lo, hi, plane)) return false;
  return true;
}

// Whether the segment o + t·d, t in [0, 1], meets the box (slab test).
inline bool segment_meets_box(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& lo,
                              const glm::dvec3& hi) {
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      if (o[k] < lo[k] || o[k] > hi[k]) return false;
      continue;
    }
    double ta = (lo[k] - o[k]) / d[k], tb = (hi[k] - o[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace sb::reference::detail
