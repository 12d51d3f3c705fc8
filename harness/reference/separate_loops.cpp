#include "reference/separate_loops.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace sb::reference::detail {

namespace {

using ClipperLib::cInt;
using ClipperLib::IntPoint;
using ClipperLib::Path;

// Differences of coordinates reach 2^32, their products 2^64.
__extension__ using Wide = __int128;

// The sign of twice the signed area of abc: +1 counter-clockwise.
int orientation(const IntPoint& a, const IntPoint& b, const IntPoint& c) {
  const Wide v = Wide(b.X - a.X) * Wide(c.Y - a.Y) - Wide(b.Y - a.Y) * Wide(c.X - a.X);
  return v > 0 ? 1 : v < 0 ? -1 : 0;
}

// Whether c, on the line through a and b, lies on the segment ab.
bool within(const IntPoint& a, const IntPoint& b, const IntPoint& c) {
  return std::min(a.X, b.X) <= c.X && c.X <= std::max(a.X, b.X) && std::min(a.Y, b.Y) <= c.Y &&
         c.Y <= std::max(a.Y, b.Y);
}

// Whether the closed segments ab and cd share a point.
bool segments_meet(const IntPoint& a, const IntPoint& b, const IntPoint& c, const IntPoint& d) {
  const int oa = orientation(c, d, a), ob = orientation(c, d, b), oc = orientation(a, b, c),
            od = orientation(a, b, d);
  if (oa * ob < 0 && oc * od < 0) return true;
  return (oa == 0 && within(c, d, a)) || (ob == 0 && within(c, d, b)) ||
         (oc == 0 && within(a, b, c)) || (od == 0 && within(a, b, d));
}

// Whether p, on none of its edges, lies inside the simple loop (the
// crossings of the ray from p towards +x, each edge half-open in y).
bool inside(const Path& loop, const IntPoint& p) {
  bool in = false;
  for (size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
    const IntPoint &a = loop[j], &b = loop[i];
    if ((a.Y > p.Y) != (b.Y > p.Y)) {
      const int o = orientation(a, b, p);
      if (b.Y > a.Y ? o > 0 : o < 0) in = !in;
    }
  }
  return in;
}

// Twice the loop's signed area (positive counter-clockwise), exactly.
Wide twice_area(const Path& loop) {
  Wide sum = 0;
  for (size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++)
    sum += Wide(loop[j].X + loop[i].X) * Wide(loop[i].Y - loop[j].Y);
  return sum;
}

}  // namespace

std::optional<double> separate_loops_area(const ClipperLib::Paths& loops, size_t count) {
  // Beyond a few loops the containment tests cost more than they save.
  constexpr size_t kMostLoops = 16;
  if (count == 0 || count > kMostLoops) return std::nullopt;
  struct Edge {
    cInt lo_x, hi_x, lo_y, hi_y;
    uint32_t loop, index;
  };
  thread_local std::vector<Edge> edges;
  edges.clear();
  for (size_t k = 0; k < count; ++k) {
    const Path& loop = loops[k];
    const size_t n = loop.size();
    if (n < 3) return std::nullopt;
    for (size_t i = 0; i < n; ++i) {
      const IntPoint &u = loop[(i + n - 1) % n], &v = loop[i], &w = loop[(i + 1) % n];
      if (v == w) return std::nullopt;  // an edge of no length
      // A corner where the outline doubles back along itself.
      if (orientation(u, v, w) == 0 &&
          Wide(v.X - u.X) * Wide(w.X - v.X) + Wide(v.Y - u.Y) * Wide(w.Y - v.Y) <= 0)
        return std::nullopt;
      edges.push_back({std::min(v.X, w.X), std::max(v.X, w.X), std::min(v.Y, w.Y),
                       std::max(v.Y, w.Y), uint32_t(k), uint32_t(i)});
    }
  }
  // Every two edges whose boxes overlap, found by a sweep along x; two
  // edges of one loop that follow each other meet only at their common
  // corner, the doubling back being ruled out above.
  std::sort(edges.begin(), edges.end(),
            [](const Edge& x, const Edge& y) { return x.lo_x < y.lo_x; });
  for (size_t i = 0; i < edges.size(); ++i) {
    const Edge& e = edges[i];
    for (size_t j = i + 1; j < edges.size() && edges[j].lo_x <= e.hi_x; ++j) {
      const Edge& g = edges[j];
      if (g.lo_y > e.hi_y || g.hi_y < e.lo_y) continue;
      if (g.loop == e.loop) {
        const size_t n = loops[e.loop].size();
        const uint32_t gap = e.index > g.index ? e.index - g.index : g.index - e.index;
        if (gap == 1 || gap == n - 1) continue;
      }
      const Path &a = loops[e.loop], &b = loops[g.loop];
      if (segments_meet(a[e.index], a[(e.index + 1) % a.size()], b[g.index],
                        b[(g.index + 1) % b.size()]))
        return std::nullopt;
    }
  }
  if (count == 1) {
    const Wide twice = twice_area(loops[0]);
    return 0.5 * static_cast<double>(twice < 0 ? -twice : twice);
  }
  Wide sum = 0;
  for (size_t k = 0; k < count; ++k) {
    const Wide twice = twice_area(loops[k]);
    if (twice <= 0) return std::nullopt;  // a hole, or wound the other way
    sum += twice;
  }
  // No two touch, so a loop lies inside another exactly when its first
  // corner does.
  for (size_t k = 0; k < count; ++k)
    for (size_t m = 0; m < count; ++m)
      if (m != k && inside(loops[m], loops[k][0])) return std::nullopt;
  return 0.5 * static_cast<double>(sum);
}

}  // namespace sb::reference::detail
