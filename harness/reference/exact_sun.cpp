// The exact V of the sun (exact_visibility.h): the casters' triangles
// clipped to the pyramid from the point around the sun's cone, projected
// along their directions onto the plane at unit distance along the sun's
// axis, their union by Clipper, and the part of the union inside the sun's
// disk in closed form.
#include <algorithm>
#include <clipper.hpp>
#include <cmath>
#include <numbers>
#include <utility>

#include "reference/closed_parts.h"
#include "reference/exact_visibility.h"

namespace sb::reference {

namespace {

using detail::CasterTriangle;
using detail::PartCrossings;
using detail::Plane;
using detail::Polygon3;

constexpr double kDiskIntegerRange = 1073741824.0;  // 2^30: the disk's radius

double cross2(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

// The signed area of triangle (0, a, b) inside the disk of radius r about
// 0. The line through a and b meets the circle at t1 < t2 (a + t·(b − a)):
// the segment's part between them is inside and counts as its triangle with
// 0; the parts before and after are outside and count as the circular
// sectors they span. A line that misses or only touches the circle is
// outside along its whole length.
double triangle_in_disk(const glm::dvec2& a, const glm::dvec2& b, double r) {
  const glm::dvec2 d = b - a;
  const double qa = glm::dot(d, d), qb = 2.0 * glm::dot(a, d), qc = glm::dot(a, a) - r * r;
  const double disc = qb * qb - 4.0 * qa * qc;
  const auto sector = [r](const glm::dvec2& p, const glm::dvec2& q) {
    return 0.5 * r * r * std::atan2(cross2(p, q), glm::dot(p, q));
  };
  if (!(qa > 0.0) || !(disc > 0.0)) return sector(a, b);
  const double root = std::sqrt(disc);
  const double t1 = std::clamp((-qb - root) / (2.0 * qa), 0.0, 1.0);
  const double t2 = std::clamp((-qb + root) / (2.0 * qa), 0.0, 1.0);
  const glm::dvec2 p1 = a + t1 * d, p2 = a + t2 * d;
  return sector(a, p1) + 0.5 * cross2(p1, p2) + sector(p2, b);
}

}  // namespace

double ExactVisibility::disk_area_inside(const std::vector<glm::dvec2>& polygon, double radius) {
  double area = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i)
    area += triangle_in_disk(polygon[i], polygon[(i + 1) % polygon.size()], radius);
  return area;
}

double ExactVisibility::union_disk_area(const std::vector<std::vector<glm::dvec2>>& polygons,
                                        double radius) {
  const double scale = kDiskIntegerRange / radius;
  const double square = (2.0 * kDiskIntegerRange) * (2.0 * kDiskIntegerRange);
  const double disk = std::numbers::pi * radius * radius;
  ClipperLib::Paths paths;
  paths.reserve(polygons.size());
  for (const auto& polygon : polygons) {
    ClipperLib::Path path;
    path.reserve(polygon.size());
    for (const glm::dvec2& q : polygon)
      path.emplace_back(ClipperLib::cInt(std::llround(q.x * scale)),
                        ClipperLib::cInt(std::llround(q.y * scale)));
    const double area = ClipperLib::Area(path);
    // One polygon covers the square around the disk: the union is the disk.
    if (area >= square * (1.0 - 1e-12)) return disk;
    if (area > 0.0) paths.push_back(std::move(path));
  }
  ClipperLib::Clipper clipper;
  clipper.AddPaths(paths, ClipperLib::ptSubject, true);
  ClipperLib::Paths united;
  clipper.Execute(ClipperLib::ctUnion, united, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  // Outer boundaries run counter-clockwise and holes clockwise, so the
  // signed parts inside the disk add up to the union's.
  double covered = 0.0;
  std::vector<glm::dvec2> corners;
  for (const auto& path : united) {
    corners.clear();
    for (const auto& q : path) corners.emplace_back(double(q.X) / scale, double(q.Y) / scale);
    covered += disk_area_inside(corners, radius);
  }
  return std::clamp(covered, 0.0, disk);
}

std::vector<std::vector<glm::dvec2>> ExactVisibility::sun_occluding_polygons(
    const glm::dvec3& surface, const glm::dvec3& n) const {
  std::vector<std::vector<glm::dvec2>> out;
  const glm::dvec3 axis = glm::normalize(glm::dvec3(light_.to_sun()));
  glm::dvec3 e1 = glm::dvec3(light_.half_u);
  e1 = glm::normalize(e1 - axis * glm::dot(e1, axis));
  const glm::dvec3 e2 = glm::cross(axis, e1);
  const double t = std::tan(0.5 * double(light_.angular_diameter));
  // Seen from just above the surface, as the Monte Carlo rays start.
  const glm::dvec3 p = viewpoint(surface, n);
  // The square around the sun's disk on the plane at unit distance from p.
  const std::array<glm::dvec3, 4> corners{p + axis + t * (-e1 - e2), p + axis + t * (e1 - e2),
                                          p + axis + t * (e1 + e2), p + axis + t * (-e1 + e2)};
  const auto add = [&](const Polygon3& poly) {
    if (poly.size() < 3) return;
    std::vector<glm::dvec2> flat;
    flat.reserve(poly.size());
    for (const glm::dvec3& x : poly) {
      const double along = glm::dot(x - p, axis);
      if (!(along > 0.0)) return;  // the apex itself: no area
      const glm::dvec3 onto = (x - p) / along;
      flat.push_back(
          {std::clamp(glm::dot(onto, e1), -t, t), std::clamp(glm::dot(onto, e2), -t, t)});
    }
    double area = 0.0;
    for (size_t i = 0; i < flat.size(); ++i) area += cross2(flat[i], flat[(i + 1) % flat.size()]);
    if (area < 0.0) std::reverse(flat.begin(), flat.end());
    if (area != 0.0) out.push_back(std::move(flat));
  };
  // The directions below the horizon (dot(n, d) <= 0), which the surface
  // itself hides.
  add(detail::clip(Polygon3(corners.begin(), corners.end()), Plane{-n, p}));
  if (casters_.empty()) return out;
  // The pyramid from p through the square's sides, and the tangent plane.
  std::array<Plane, 5> planes;
  for (size_t i = 0; i < 4; ++i) {
    glm::dvec3 m = glm::cross(corners[i] - p, corners[(i + 1) % 4] - p);
    if (glm::dot(m, axis) < 0.0) m = -m;
    planes[i] = {m, p};
  }
  // The fifth, the half-space ahead of p, only completes the box test's
  // five planes (the sides imply it): the tangent plane must not cull the
  // boxes, or the inside test below would miss crossings under it.
  planes[4] = {axis, p};
  const Plane tangent{n, surface};
  const double on_plane = 1e-12 * std::max(glm::length(p), 1.0);
  // Whether p is inside a closed part: the segment from p along the axis,
  // far past every caster, stands in for the segment to a local light's
  // centre.
  PartCrossings crossings(p, axis * (2.0 * (reach_ + glm::length(p - reach_centre_)) + 1.0));
  casters_.traverse(
      [&](const glm::dvec3& lo, const glm::dvec3& hi) { return detail::box_meets(lo, hi, planes); },
      [&](const CasterTriangle& tri) {
        const double facing = glm::dot(tri.normal, p - tri.a);
        if (tri.part != detail::kNoPart)
          crossings.add(tri.part, tri.outward, tri.a, tri.b, tri.c, tri.normal);
        if (std::fabs(facing) <= on_plane * glm::length(tri.normal)) return;
        if (double(tri.outward) * facing < 0.0) return;  // a closed caster's far side
        Polygon3 poly{tri.a, tri.b, tri.c};
        for (size_t i = 0; i < 4; ++i) poly = detail::clip(poly, planes[i]);
        add(detail::clip(poly, tangent));
      });
  if (crossings.winds_around_start()) return {{{-t, -t}, {t, -t}, {t, t}, {-t, t}}};
  return out;
}

double ExactVisibility::sun_visibility(const glm::dvec3& p, const glm::dvec3& n) const {
  const auto polygons = sun_occluding_polygons(p, n);
  if (polygons.empty()) return 1.0;
  const double r = std::tan(0.5 * double(light_.angular_diameter));
  return std::clamp(1.0 - union_disk_area(polygons, r) / (std::numbers::pi * r * r), 0.0, 1.0);
}

}  // namespace sb::reference
