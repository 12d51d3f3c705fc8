// The exact V of a rectangular light (exact_visibility.h): the casters'
// triangles clipped to the pyramid from the point to the light, projected
// onto the light's plane, and their union's area, by Clipper.
#include <algorithm>
#include <clipper.hpp>
#include <cmath>
#include <utility>

#include "reference/closed_parts.h"
#include "reference/exact_visibility.h"
#include "reference/light_frame.h"

namespace sb::reference {

namespace {

using detail::CasterTriangle;
using detail::Frame;
using detail::kNoPart;
using detail::PartCrossings;
using detail::Plane;
using detail::Polygon3;

constexpr double kIntegerRange = 1073741824.0;  // 2^30: the light's larger half-size

}  // namespace

std::vector<std::vector<glm::dvec2>> ExactVisibility::occluding_polygons(
    const glm::dvec3& surface, const glm::dvec3& n) const {
  std::vector<std::vector<glm::dvec2>> out;
  const Frame f(light_);
  // The light below the tangent plane through the surface point.
  const auto corners = f.corners();
  const Polygon3 below = detail::clip(Polygon3(corners.begin(), corners.end()), Plane{-n, surface});
  // The occluders are seen from just above the surface, as the Monte Carlo
  // reference's shadow rays start (ray_offset.h's 2^-16 relative offset):
  // from the point itself, a neighbouring facet of a convex mesh, which
  // meets it at an edge within rounding of p, would project onto half the
  // light.
  const glm::dvec3 p = viewpoint(surface, n);
  const double zp = glm::dot(p - f.centre, f.normal);
  // The pyramid culls the hierarchy's boxes. Triangles are clipped to it and
  // to the tangent plane through the surface point: whatever lies below that
  // plane projects, from p above it, into the light's part below it, which
  // the horizon polygon already covers.
  const auto planes = detail::pyramid(f, p);
  const Plane tangent{n, surface};
  const auto add = [&](const Polygon3& poly, bool project) {
    if (poly.size() < 3) return;
    std::vector<glm::dvec2> flat;
    flat.reserve(poly.size());
    for (const glm::dvec3& x : poly) {
      glm::dvec3 onto = x;
      if (project) {
        const double dz = zp - glm::dot(x - f.centre, f.normal);
        if (!(std::fabs(dz) > 0.0)) return;  // the apex itself: no area
        onto = p + (x - p) * (zp / dz);
      }
      const glm::dvec2 q = f.plane_coords(onto);
      flat.push_back({std::clamp(q.x, -f.hw, f.hw), std::clamp(q.y, -f.hh, f.hh)});
    }
    double area = 0.0;
    for (size_t i = 0; i < flat.size(); ++i) {
      const glm::dvec2 &a = flat[i], &b = flat[(i + 1) % flat.size()];
      area += a.x * b.y - a.y * b.x;
    }
    if (area < 0.0) std::reverse(flat.begin(), flat.end());
    if (area != 0.0) out.push_back(std::move(flat));
  };
  add(below, false);
  // From the light's own plane the light has no solid angle: nothing projects.
  if (zp == 0.0 || casters_.empty()) return out;
  // Triangles whose plane passes this close to p contain it, as seen from
  // p: their projection has no area.
  const double on_plane = 1e-12 * std::max(glm::length(p), 1.0);
  // Whether p is inside a closed part that the light is outside of
  // (PartCrossings), by the segment from p to the light's centre. It lies
  // in the pyramid, so every triangle it can cross is visited.
  const glm::dvec3 to_centre = f.centre - p;
  PartCrossings crossings(p, to_centre);
  casters_.traverse(
      [&](const glm::dvec3& lo, const glm::dvec3& hi) { return detail::box_meets(lo, hi, planes); },
      [&](const CasterTriangle& t) {
        const glm::dvec3& normal = t.normal;
        const double facing = glm::dot(normal, p - t.a);
        if (t.part != kNoPart) crossings.add(t.part, t.outward, t.a, t.b, t.c, normal);
        if (std::fabs(facing) <= on_plane * glm::length(normal)) return;
        if (double(t.outward) * facing < 0.0) return;  // a closed caster's far side
        if (glm::dot(n, t.a - surface) < 0.0 && glm::dot(n, t.b - surface) < 0.0 &&
            glm::dot(n, t.c - surface) < 0.0)
          return;  // below the tangent plane: inside the horizon polygon
        Polygon3 poly{t.a, t.b, t.c};
        for (const Plane& plane : planes) poly = detail::clip(poly, plane);
        add(detail::clip(poly, tangent), true);
      });
  // Inside a closed part every ray towards the light is blocked.
  if (crossings.winds_around_start())
    return {{{-f.hw, -f.hh}, {f.hw, -f.hh}, {f.hw, f.hh}, {-f.hw, f.hh}}};
  return out;
}

double ExactVisibility::union_area(const std::vector<std::vector<glm::dvec2>>& polygons,
                                   double half_width, double half_height) {
  const double scale = kIntegerRange / std::max(half_width, half_height);
  const double light_area = (2.0 * half_width * scale) * (2.0 * half_height * scale);
  ClipperLib::Paths paths;
  paths.reserve(polygons.size());
  for (const auto& polygon : polygons) {
    ClipperLib::Path path;
    path.reserve(polygon.size());
    for (const glm::dvec2& q : polygon)
      path.emplace_back(ClipperLib::cInt(std::llround(q.x * scale)),
                        ClipperLib::cInt(std::llround(q.y * scale)));
    const double area = ClipperLib::Area(path);
    // One polygon covers the light: the union is the light.
    if (area >= light_area * (1.0 - 1e-12)) return 4.0 * half_width * half_height;
    if (area > 0.0) paths.push_back(std::move(path));
  }
  ClipperLib::Clipper clipper;
  clipper.AddPaths(paths, ClipperLib::ptSubject, true);
  ClipperLib::Paths united;
  clipper.Execute(ClipperLib::ctUnion, united, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  double covered = 0.0;
  for (const auto& path : united) covered += ClipperLib::Area(path);
  return std::clamp(covered, 0.0, light_area) / (scale * scale);
}

}  // namespace sb::reference
