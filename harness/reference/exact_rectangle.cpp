// The exact V of a rectangular light (exact_visibility.h): the casters'
// triangles clipped to the pyramid from the point to the light, projected
// onto the light's plane, and their union's area, by Clipper.
#include <algorithm>
#include <array>
#include <bit>
#include <clipper.hpp>
#include <cmath>
#include <cstddef>
#include <optional>
#include <utility>

#include "reference/closed_parts.h"
#include "reference/exact_visibility.h"
#include "reference/light_frame.h"
#include "reference/separate_loops.h"

namespace sb::reference {

namespace {

using detail::CasterTriangle;
using detail::Frame;
using detail::kNoPart;
using detail::PartCrossings;
using detail::Plane;
using detail::Polygon3;

constexpr double kIntegerRange = 1073741824.0;  // 2^30: the light's larger half-size

using ClipperLib::IntPoint;

// std::llround (halves away from zero) without the library call, which
// cost a tenth of the union's instructions: x minus its truncation is exact.
ClipperLib::cInt round_to_integer(double x) {
  const auto whole = static_cast<ClipperLib::cInt>(x);  // towards zero
  const double rest = x - static_cast<double>(whole);
  return rest >= 0.5 ? whole + 1 : rest <= -0.5 ? whole - 1 : whole;
}

bool operator<(const IntPoint& a, const IntPoint& b) {
  return a.X < b.X || (a.X == b.X && a.Y < b.Y);
}

// The first `count` of `paths` as closed loops without the edges that two
// of them run along in opposite directions (neighbouring triangles' common
// edge, where both projected the same corners), nor edges of no length.
// The winding number about every point off the edges is the same sum
// (removing an edge and its reverse changes none), and so is the union
// that Clipper's non-zero rule reads from it, with less work: a closed
// part's projected triangles tile its shadow, and only the shadow's
// outline remains. The loops go into the first of `loops` (kept with their
// capacity); returns how many.
size_t cancel_shared_edges(const ClipperLib::Paths& paths, size_t count, ClipperLib::Paths& loops) {
  struct Edge {
    IntPoint lo, hi;  // lo < hi
    bool forward;     // runs from lo to hi
    bool kept;
  };
  thread_local std::vector<Edge> edges;
  thread_local std::vector<uint32_t> order;
  edges.clear();
  for (size_t k = 0; k < count; ++k) {
    const ClipperLib::Path& path = paths[k];
    for (size_t i = 0; i < path.size(); ++i) {
      const IntPoint& a = path[i];
      const IntPoint& b = path[(i + 1) % path.size()];
      if (a == b) continue;
      edges.push_back(a < b ? Edge{a, b, true, true} : Edge{b, a, false, true});
    }
  }
  // Pairs of opposite edges on the same two corners cancel.
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
    return x.lo < y.lo ||
           (x.lo == y.lo && (x.hi < y.hi || (x.hi == y.hi && x.forward < y.forward)));
  });
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
    // [i, j): the backward ones first, then the forward ones.
    size_t back = i, fore = i;
    while (fore < j && !edges[fore].forward) ++fore;
    for (size_t b = back, f = fore; b < fore && f < j; ++b, ++f)
      edges[b].kept = edges[f].kept = false;
    i = j;
  }
  // The rest, walked into loops from their starting corners: every corner
  // has as many edges leaving as arriving, so a walk ends where it began.
  order.clear();
  for (uint32_t e = 0; e < edges.size(); ++e)
    if (edges[e].kept) order.push_back(e);
  const auto from = [](const Edge& e) { return e.forward ? e.lo : e.hi; };
  const auto to = [](const Edge& e) { return e.forward ? e.hi : e.lo; };
  std::sort(order.begin(), order.end(),
            [&](uint32_t x, uint32_t y) { return from(edges[x]) < from(edges[y]); });
  size_t loop_count = 0;
  for (const uint32_t start : order) {
    if (!edges[start].kept) continue;
    if (loop_count == loops.size()) loops.emplace_back();
    ClipperLib::Path& loop = loops[loop_count++];
    loop.clear();
    const IntPoint origin = from(edges[start]);
    uint32_t e = start;
    while (true) {
      edges[e].kept = false;
      loop.push_back(from(edges[e]));
      const IntPoint corner = to(edges[e]);
      if (corner == origin) break;
      auto it = std::lower_bound(order.begin(), order.end(), corner,
                                 [&](uint32_t x, const IntPoint& c) { return from(edges[x]) < c; });
      while (it != order.end() && !edges[*it].kept && from(edges[*it]) == corner) ++it;
      if (it == order.end() || from(edges[*it]) != corner) {
        // Unbalanced (cannot happen): the paths as they were.
        loops.assign(paths.begin(), paths.begin() + std::ptrdiff_t(count));
        return count;
      }
      e = *it;
    }
  }
  return loop_count;
}

}  // namespace

std::vector<std::vector<glm::dvec2>> ExactVisibility::occluding_polygons(
    const glm::dvec3& surface, const glm::dvec3& n) const {
  FlatPolygons flat;
  collect_polygons(surface, n, viewpoint(surface, n), flat);
  std::vector<std::vector<glm::dvec2>> out;
  uint32_t first = 0;
  for (const uint32_t end : flat.ends) {
    out.emplace_back(flat.corners.begin() + first, flat.corners.begin() + end);
    first = end;
  }
  return out;
}

void ExactVisibility::collect_polygons(const glm::dvec3& surface, const glm::dvec3& n,
                                       const glm::dvec3& origin, FlatPolygons& out,
                                       const std::vector<detail::CasterBvh::Leaf>* leaves) const {
  out.clear();
  const Frame& f = frame_;
  // The light below the tangent plane through the surface point.
  const auto& corners = corners_;
  std::array<glm::dvec3, 8> below{};
  const size_t below_count =
      detail::clip_into(corners.data(), corners.size(), Plane{-n, surface}, below.data());
  // The occluders are seen from just above the surface, as the Monte Carlo
  // reference's shadow rays start (ray_offset.h's 2^-16 relative offset):
  // from the point itself, a neighbouring facet of a convex mesh, which
  // meets it at an edge within rounding of p, would project onto half the
  // light.
  const glm::dvec3& p = origin;
  const double zp = glm::dot(p - f.centre, f.normal);
  // The pyramid culls the hierarchy's boxes. Triangles are clipped to it and
  // to the tangent plane through the surface point: whatever lies below that
  // plane projects, from p above it, into the light's part below it, which
  // the horizon polygon already covers.
  const auto planes = detail::pyramid(f, p);
  const Plane tangent{n, surface};
  const std::array<const Plane*, 6> cuts{&planes[0], &planes[1], &planes[2],
                                         &planes[3], &planes[4], &tangent};
  // Appends the polygon of `count` corners, projected from p onto the
  // light's plane when `project`, counter-clockwise; nothing when it has no
  // area.
  const auto add = [&](const glm::dvec3* poly, size_t count, bool project) {
    if (count < 3) return;
    const size_t first = out.corners.size();
    for (size_t i = 0; i < count; ++i) {
      glm::dvec3 onto = poly[i];
      if (project) {
        const double dz = zp - glm::dot(poly[i] - f.centre, f.normal);
        if (!(std::fabs(dz) > 0.0)) {  // the apex itself: no area
          out.corners.resize(first);
          return;
        }
        onto = p + (poly[i] - p) * (zp / dz);
      }
      const glm::dvec2 q = f.plane_coords(onto);
      out.corners.push_back({std::clamp(q.x, -f.hw, f.hw), std::clamp(q.y, -f.hh, f.hh)});
    }
    const glm::dvec2* flat = out.corners.data() + first;
    double area = 0.0;
    for (size_t i = 0; i < count; ++i) {
      const glm::dvec2 &a = flat[i], &b = flat[(i + 1) % count];
      area += a.x * b.y - a.y * b.x;
    }
    if (area == 0.0) {
      out.corners.resize(first);
      return;
    }
    if (area < 0.0) std::reverse(out.corners.begin() + std::ptrdiff_t(first), out.corners.end());
    out.ends.push_back(uint32_t(out.corners.size()));
  };
  add(below.data(), below_count, false);
  // From the light's own plane the light has no solid angle: nothing projects.
  if (zp == 0.0 || casters_.empty()) return;
  // Triangles whose plane passes this close to p contain it, as seen from
  // p: their projection has no area.
  const double on_plane = 1e-12 * std::max(glm::length(p), 1.0);
  // Whether p is inside a closed part that the light is outside of
  // (PartCrossings), by the segment from p to the light's centre. It lies
  // in the pyramid, so every triangle it can cross is visited.
  const glm::dvec3 to_centre = f.centre - p;
  PartCrossings crossings(p, to_centre);
  // The pyramid's bounding box: a box outside it cannot meet the pyramid,
  // nor the segment inside it, and its cheaper test comes first.
  glm::dvec3 reach_lo = p, reach_hi = p;
  for (const glm::dvec3& corner : corners) {
    reach_lo = glm::min(reach_lo, corner);
    reach_hi = glm::max(reach_hi, corner);
  }
  const auto keep = [&](const glm::dvec3& lo, const glm::dvec3& hi) {
    return lo.x <= reach_hi.x && lo.y <= reach_hi.y && lo.z <= reach_hi.z && reach_lo.x <= hi.x &&
           reach_lo.y <= hi.y && reach_lo.z <= hi.z && detail::box_meets(lo, hi, planes);
  };
  // `may_cross`: whether the segment to the light's centre may cross t.
  const auto visit = [&](const CasterTriangle& t, bool may_cross) {
    const glm::dvec3& normal = t.normal;
    const double facing = glm::dot(normal, p - t.a);
    if (may_cross && t.part != kNoPart) crossings.add(t.part, t.outward, t.a, t.b, t.c, normal);
    if (double(t.outward) * facing < 0.0) return;  // a closed caster's far side
    if (std::fabs(facing) <= on_plane * glm::length(normal)) return;
    if (glm::dot(n, t.a - surface) < 0.0 && glm::dot(n, t.b - surface) < 0.0 &&
        glm::dot(n, t.c - surface) < 0.0)
      return;  // below the tangent plane: inside the horizon polygon
    // Wholly outside one plane: nothing; inside all: the triangle itself,
    // as clipping would leave them.
    bool inside = true;
    for (const Plane* plane : cuts) {
      const double da = plane->distance(t.a), db = plane->distance(t.b), dc = plane->distance(t.c);
      if (da < 0.0 && db < 0.0 && dc < 0.0) return;
      inside = inside && da >= 0.0 && db >= 0.0 && dc >= 0.0;
    }
    if (inside) {
      const std::array<glm::dvec3, 3> whole{t.a, t.b, t.c};
      add(whole.data(), 3, true);
      return;
    }
    // Clipped on two buffers: a plane adds at most one corner to a convex
    // polygon, so 3 + 6 in all; one made a little concave by rounding
    // may gain more, and takes the allocating path when the buffers
    // could overflow.
    constexpr size_t kRoom = 32;
    std::array<glm::dvec3, kRoom> one, two;  // uninitialised: clip_into writes first
    one[0] = t.a;
    one[1] = t.b;
    one[2] = t.c;
    glm::dvec3 *in = one.data(), *next = two.data();
    size_t count = 3;
    for (size_t k = 0; k < cuts.size(); ++k) {
      if (2 * count > kRoom) {
        Polygon3 poly(in, in + count);
        for (; k < cuts.size(); ++k) poly = detail::clip(poly, *cuts[k]);
        add(poly.data(), poly.size(), true);
        return;
      }
      count = detail::clip_into(in, count, *cuts[k], next);
      std::swap(in, next);
    }
    add(in, count, true);
  };
  if (leaves != nullptr) {
    // A triangle far outside the pyramid adds nothing (no polygon, no
    // crossing), so the tile's leaves give the same polygons as the walk.
    // The segment crosses no triangle of a leaf whose box, grown by far
    // more than the crossing test's rounding, it misses.
    const double margin =
        1e-9 * std::max({extent_, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z),
                         std::fabs(f.centre.x), std::fabs(f.centre.y), std::fabs(f.centre.z)});
    casters_.traverse_leaves(*leaves, keep,
                             [&](const glm::dvec3& lo, const glm::dvec3& hi,
                                 const CasterTriangle* first, uint32_t kept) {
                               const bool may_cross = detail::segment_meets_box(
                                   p, to_centre, lo - margin, hi + margin);
                               for (; kept != 0; kept &= kept - 1)
                                 visit(first[std::countr_zero(kept)], may_cross);
                             });
  } else {
    casters_.traverse(keep, [&](const CasterTriangle& t) { visit(t, true); });
  }
  // Inside a closed part every ray towards the light is blocked.
  if (crossings.winds_around_start()) {
    out.clear();
    out.corners = {{-f.hw, -f.hh}, {f.hw, -f.hh}, {f.hw, f.hh}, {-f.hw, f.hh}};
    out.ends = {4};
  }
}

double ExactVisibility::union_area(const std::vector<std::vector<glm::dvec2>>& polygons,
                                   double half_width, double half_height) {
  FlatPolygons flat;
  for (const auto& polygon : polygons) {
    flat.corners.insert(flat.corners.end(), polygon.begin(), polygon.end());
    flat.ends.push_back(uint32_t(flat.corners.size()));
  }
  return union_area(flat, half_width, half_height);
}

double ExactVisibility::union_area(const FlatPolygons& polygons, double half_width,
                                   double half_height) {
  const double scale = kIntegerRange / std::max(half_width, half_height);
  const double light_area = (2.0 * half_width * scale) * (2.0 * half_height * scale);
  // Kept per thread with their capacity: the first `used` are this call's.
  thread_local ClipperLib::Paths paths;
  size_t used = 0;
  uint32_t first = 0;
  for (const uint32_t end : polygons.ends) {
    if (used == paths.size()) paths.emplace_back();
    ClipperLib::Path& path = paths[used];
    path.clear();
    for (uint32_t i = first; i < end; ++i) {
      const glm::dvec2& q = polygons.corners[i];
      path.emplace_back(round_to_integer(q.x * scale), round_to_integer(q.y * scale));
    }
    first = end;
    const double area = ClipperLib::Area(path);
    // One polygon covers the light: the union is the light.
    if (area >= light_area * (1.0 - 1e-12)) return 4.0 * half_width * half_height;
    if (area > 0.0) ++used;
  }
  double covered = 0.0;
  if (used == 1) {
    // One polygon is its own union.
    covered = ClipperLib::Area(paths[0]);
  } else {
    thread_local ClipperLib::Paths loops;
    const size_t loop_count = cancel_shared_edges(paths, used, loops);
    // Usually a shadow's outline, or a few apart: their areas, no Clipper.
    if (const std::optional<double> separate = detail::separate_loops_area(loops, loop_count)) {
      covered = *separate;
    } else {
      ClipperLib::Clipper clipper;
      for (size_t i = 0; i < loop_count; ++i)
        clipper.AddPath(loops[i], ClipperLib::ptSubject, true);
      thread_local ClipperLib::Paths united;
      united.clear();
      clipper.Execute(ClipperLib::ctUnion, united, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
      for (const auto& path : united) covered += ClipperLib::Area(path);
    }
  }
  return std::clamp(covered, 0.0, light_area) / (scale * scale);
}

}  // namespace sb::reference
