// The exact V of a linear light (exact_visibility.h): each candidate
// triangle's cut by the plane through the point and the segment, projected
// onto the segment, and the union's length.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "reference/closed_parts.h"
#include "reference/exact_visibility.h"

namespace sb::reference {

namespace {

using detail::below;
using detail::box_outside;
using detail::CasterTriangle;
using detail::clip_segment;
using detail::kNoPart;
using detail::PartCrossings;
using detail::Plane;
using detail::segment_crossing;
using detail::segment_meets_box;

}  // namespace

std::vector<glm::dvec2> ExactVisibility::hidden_intervals(const glm::dvec3& surface,
                                                          const glm::dvec3& n) const {
  std::vector<glm::dvec2> out;
  const glm::dvec3 a_end(light_.segment_end(0.0f)), b_end(light_.segment_end(1.0f));
  glm::dvec2 interval;
  // The horizon: the part of the segment below the tangent plane.
  if (below(glm::dot(n, a_end - surface), glm::dot(n, b_end - surface), interval))
    out.push_back(interval);
  if (casters_.empty()) return out;
  // Seen from just above the surface, as for a rectangle (occluding_polygons).
  const glm::dvec3 p = viewpoint(surface, n);
  const double on_plane = 1e-12 * std::max(glm::length(p), 1.0);
  const Plane tangent{n, surface};
  const glm::dvec3 a = a_end - p, b = b_end - p;
  const glm::dvec3 m = glm::cross(a, b);  // the plane of p, A and B
  const double ml = glm::length(m);

  // The inside-a-closed-part test of occluding_polygons, on the segment to
  // the light's centre (the segment's midpoint).
  const glm::dvec3 to_centre = glm::dvec3(light_.center) - p;
  PartCrossings crossings(p, to_centre);
  // Whether a triangle can hide anything; notes its crossing for the test.
  const auto candidate = [&](const CasterTriangle& t) {
    const glm::dvec3& normal = t.normal;
    if (t.part != kNoPart) crossings.add(t.part, t.outward, t.a, t.b, t.c, normal);
    const double facing = glm::dot(normal, p - t.a);
    if (std::fabs(facing) <= on_plane * glm::length(normal)) return false;  // contains p
    if (double(t.outward) * facing < 0.0) return false;  // a closed caster's far side
    // Wholly below the tangent plane: inside the horizon interval.
    return !(glm::dot(n, t.a - surface) < 0.0 && glm::dot(n, t.b - surface) < 0.0 &&
             glm::dot(n, t.c - surface) < 0.0);
  };

  if (!(ml > 1e-7 * glm::length(a) * glm::length(b))) {
    // p on the segment's line: every ray runs along it, and in each
    // direction the nearest crossing hides the rest of the segment.
    const glm::dvec3 axis = b_end - a_end;
    const double length = glm::length(axis);
    if (!(length > 0.0)) return out;
    const double xa = glm::dot(a, axis) / length, xb = glm::dot(b, axis) / length;
    double t_a = std::numeric_limits<double>::infinity(), t_b = t_a;  // along p→A, p→B
    casters_.traverse(
        [&](const glm::dvec3& lo, const glm::dvec3& hi) {
          return (xa < 0.0 && segment_meets_box(p, a, lo, hi)) ||
                 (xb > 0.0 && segment_meets_box(p, b, lo, hi)) ||
                 segment_meets_box(p, to_centre, lo, hi);
        },
        [&](const CasterTriangle& t) {
          if (!candidate(t)) return;
          if (xa < 0.0) t_a = std::min(t_a, segment_crossing(p, a, t.a, t.b, t.c));
          if (xb > 0.0) t_b = std::min(t_b, segment_crossing(p, b, t.a, t.b, t.c));
        });
    if (crossings.winds_around_start()) return {{0.0, 1.0}};
    if (t_a <= 1.0) out.push_back({0.0, (t_a * xa - xa) / (xb - xa)});
    if (t_b <= 1.0) out.push_back({(t_b * xb - xa) / (xb - xa), 1.0});
    return out;
  }

  // The wedge from p to the segment: its sides through p and each end, the
  // plane through A and B (p's side), and the plane of p, A and B from both
  // sides, which a box must straddle.
  const Plane side_a{glm::cross(m, a), p}, side_b{glm::cross(b, m), p};
  glm::dvec3 far_normal = glm::cross(b - a, m);
  if (glm::dot(far_normal, p - a_end) < 0.0) far_normal = -far_normal;
  const Plane far{far_normal, a_end};
  const glm::dvec3 unit = m / ml;
  const std::array<Plane, 5> planes{side_a, side_b, far, Plane{unit, p}, Plane{-unit, p}};
  casters_.traverse(
      [&](const glm::dvec3& lo, const glm::dvec3& hi) {
        for (const Plane& plane : planes)
          if (box_outside(lo, hi, plane)) return false;
        return true;
      },
      [&](const CasterTriangle& t) {
        if (!candidate(t)) return;
        // The triangle's cut by the plane of p, A and B.
        const std::array<glm::dvec3, 3> x{t.a, t.b, t.c};
        const std::array<double, 3> d{glm::dot(unit, t.a - p), glm::dot(unit, t.b - p),
                                      glm::dot(unit, t.c - p)};
        if (d[0] == 0.0 && d[1] == 0.0 && d[2] == 0.0) return;  // in the plane: hides nothing
        std::array<glm::dvec3, 3> cut;
        size_t count = 0;
        for (size_t i = 0; i < 3; ++i) {
          const size_t j = (i + 1) % 3;
          if (d[i] == 0.0) cut[count++] = x[i];
          if ((d[i] < 0.0 && d[j] > 0.0) || (d[i] > 0.0 && d[j] < 0.0))
            cut[count++] = x[i] + (x[j] - x[i]) * (d[i] / (d[i] - d[j]));
        }
        if (count < 2) return;
        // Its part between p and the segment, above the tangent plane.
        const glm::dvec2 range = clip_segment(cut[0], cut[1], {&side_a, &side_b, &far, &tangent});
        if (!(range.x <= range.y)) return;
        // Projected from p onto the line AB: x − p = α·a + β·b gives s = β / (α + β).
        const auto project = [&](double k) {
          const glm::dvec3 v = cut[0] + (cut[1] - cut[0]) * k - p;
          const double beta = glm::dot(glm::cross(a, v), m), alpha = glm::dot(glm::cross(v, b), m);
          return alpha + beta > 0.0 ? std::clamp(beta / (alpha + beta), 0.0, 1.0)
                                    : std::numeric_limits<double>::quiet_NaN();
        };
        const double s0 = project(range.x), s1 = project(range.y);
        if (std::isnan(s0) || std::isnan(s1)) return;  // reaches p itself: no extent
        out.push_back({std::min(s0, s1), std::max(s0, s1)});
      });
  if (crossings.winds_around_start()) return {{0.0, 1.0}};
  return out;
}

double ExactVisibility::union_length(std::vector<glm::dvec2> intervals) {
  // Abutting triangles' cuts meet at a point computed twice, so their
  // intervals can miss each other by rounding (1e-15): an umbra would read
  // V = 1e-15 and count as penumbra. Gaps narrower than this, and the ends'
  // last bit, are closed, as Clipper's integer grid (2^-31 of the light)
  // closes them for a rectangle.
  constexpr double kGap = 1e-9;
  std::sort(intervals.begin(), intervals.end(),
            [](const glm::dvec2& x, const glm::dvec2& y) { return x.x < y.x; });
  double covered = 0.0, lo = 0.0, hi = 0.0;
  bool open = false;
  for (const glm::dvec2& i : intervals) {
    const double x0 = i.x <= kGap ? 0.0 : i.x, x1 = i.y >= 1.0 - kGap ? 1.0 : i.y;
    if (!(x0 < x1)) continue;
    if (open && x0 <= hi + kGap) {
      hi = std::max(hi, x1);
      continue;
    }
    if (open) covered += hi - lo;
    lo = x0;
    hi = x1;
    open = true;
  }
  if (open) covered += hi - lo;
  return std::clamp(covered, 0.0, 1.0);
}

}  // namespace sb::reference
