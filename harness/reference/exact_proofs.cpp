// The adaptive reference's proofs (exact_visibility.h: sees_whole_light,
// hides_whole_light; adaptive.h): that every shadow ray from a point
// reaches the light, or that none does.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "reference/closed_parts.h"
#include "reference/exact_visibility.h"
#include "reference/light_frame.h"

namespace sb::reference {

using core::AreaLight;

namespace {

using detail::box_meets;
using detail::CasterTriangle;
using detail::clip;
using detail::Frame;
using detail::kNoNeighbour;
using detail::kNoPart;
using detail::PartCrossings;
using detail::Plane;
using detail::Polygon3;
using detail::pyramid;
using detail::segment_meets;
using detail::segment_meets_box;
using detail::triangle_meets;

constexpr double kProofWider = 1e-5;  // of the light's size, and of distances

// Where both proofs start (sees_whole_light, hides_whole_light): the light
// taken wider than the rays (1e-5 of its size each way, in its own plane),
// how far origin lies above the surface along n, the unit axis from origin
// to the light's centre, and how many of the wider light's corners lie
// clearly above and below origin's plane (by 1e-5 of their distance). Empty
// for a segment or a point light, a zero normal, an origin not above the
// surface or on the light's centre.
struct ProofStart {
  Frame light;
  double offset = 0.0;
  glm::dvec3 axis{0.0};
  int above = 0, below = 0;
};

// The pyramid from apex to the wider light, its cap moved 1e-5 of the
// light's size beyond the light's plane: it holds every ray from a point
// between apex and the light (on its axis) to a light sample. With its
// bounding box, a cheaper first test for the hierarchy's boxes.
struct ProofPyramid {
  std::array<Plane, 5> planes;
  glm::dvec3 lo{0.0}, hi{0.0};
  bool meets(const glm::dvec3& box_lo, const glm::dvec3& box_hi) const {
    return box_lo.x <= hi.x && box_lo.y <= hi.y && box_lo.z <= hi.z && lo.x <= box_hi.x &&
           lo.y <= box_hi.y && lo.z <= box_hi.z && box_meets(box_lo, box_hi, planes);
  }
};

ProofPyramid proof_pyramid(const ProofStart& s, const glm::dvec3& apex) {
  ProofPyramid p{pyramid(s.light, apex)};
  const double beyond = kProofWider * std::max(s.light.hw, s.light.hh);
  p.planes[4].point -= beyond * p.planes[4].normal;
  // The pyramid ends at the moved cap, where its section is the light's
  // scaled from apex.
  const double depth = std::fabs(glm::dot(apex - s.light.centre, s.light.normal));
  const double scale = depth > 0.0 ? (depth + beyond) / depth : 1.0;
  p.lo = p.hi = apex;
  for (const glm::dvec3& corner : s.light.corners()) {
    const glm::dvec3 x = apex + (corner - apex) * scale;
    p.lo = glm::min(p.lo, x);
    p.hi = glm::max(p.hi, x);
  }
  return p;
}

std::optional<ProofStart> proof_start(const AreaLight& light, const glm::dvec3& surface,
                                      const glm::dvec3& origin, const glm::dvec3& n) {
  if (light.is_segment() || light.is_sun()) return std::nullopt;
  ProofStart s{Frame(light)};
  Frame& f = s.light;
  const double n_length = glm::length(n);
  if (!(n_length > 0.0) || !(f.hw > 0.0) || !(f.hh > 0.0)) return std::nullopt;
  s.offset = glm::dot(n, origin - surface) / n_length;
  if (!(s.offset > 0.0)) return std::nullopt;
  const double size = std::max(f.hw, f.hh);
  f.hw += kProofWider * size;
  f.hh += kProofWider * size;
  const double axis_length = glm::length(f.centre - origin);
  if (!(axis_length > 0.0)) return std::nullopt;
  s.axis = (f.centre - origin) / axis_length;
  for (const glm::dvec3& corner : f.corners()) {
    const glm::dvec3 d = corner - origin;
    const double h = glm::dot(n, d), margin = kProofWider * n_length * glm::length(d);
    s.above += h > margin ? 1 : 0;
    s.below += h < -margin ? 1 : 0;
  }
  return s;
}

}  // namespace

bool ExactVisibility::sees_whole_light(const glm::dvec3& surface, const glm::dvec3& origin,
                                       const glm::dvec3& n) const {
  // Every light point above the ray origin's plane: the horizon test of the
  // Monte Carlo rays (pixel_rays.cpp) keeps every sample.
  const std::optional<ProofStart> start = proof_start(light_, surface, origin, n);
  if (!start || start->above != 4) return false;
  // The apex stays above the surface's tangent plane (by at least 3/4 of
  // the offset), so the surface the point lies on never meets the pyramid.
  const ProofPyramid rays = proof_pyramid(*start, origin - 0.25 * start->offset * start->axis);
  // No triangle keeps any part inside the pyramid.
  return casters_.traverse(
      [&](const glm::dvec3& lo, const glm::dvec3& hi) { return rays.meets(lo, hi); },
      [&](const CasterTriangle& t) { return !triangle_meets(t.a, t.b, t.c, rays.planes); });
}

bool ExactVisibility::hides_whole_light(const glm::dvec3& surface, const glm::dvec3& origin,
                                        const glm::dvec3& n) const {
  // The horizon: the Monte Carlo rays trace no sample below the origin's
  // plane. All of the light below it hides all of it; part of it, nothing
  // this proves.
  const std::optional<ProofStart> start = proof_start(light_, surface, origin, n);
  if (!start) return false;
  if (start->below == 4) return true;
  if (start->above != 4 || casters_.empty()) return false;
  const Frame& f = start->light;
  const double offset = start->offset;
  // The closed part the ray to the light's centre crosses first.
  const glm::dvec3 to_centre = f.centre - origin;
  PartCrossings crossings(origin, to_centre);
  double first_hit = std::numeric_limits<double>::infinity();
  const CasterTriangle* first = nullptr;
  casters_.traverse(
      [&](const glm::dvec3& lo, const glm::dvec3& hi) {
        return segment_meets_box(origin, to_centre, lo, hi);
      },
      [&](const CasterTriangle& t) {
        if (t.part == kNoPart) return;
        const double hit = crossings.add(t.part, t.outward, t.a, t.b, t.c, t.normal);
        if (hit < first_hit) {
          first_hit = hit;
          first = &t;
        }
      });
  if (first == nullptr) return false;
  // Inside a closed part: every ray leaves it (as the exact visibility has it).
  if (crossings.winds_around_start()) return true;
  // That part alone (a closed surface), whichever way it winds.
  const uint32_t part = first->part;
  const std::array<Plane, 5> rays = proof_pyramid(*start, origin).planes;
  const ProofPyramid wider = proof_pyramid(*start, origin - 0.25 * offset * start->axis);
  const auto faces = [&](const CasterTriangle& t) {
    const double facing = glm::dot(t.normal, origin - t.a);
    return facing > 0.0 ? 1 : facing < 0.0 ? -1 : 0;
  };
  return casters_.traverse(
      [&](const glm::dvec3& lo, const glm::dvec3& hi) { return wider.meets(lo, hi); },
      [&](const CasterTriangle& t) {
        if (t.part != part) return true;
        // Reaching the light's plane inside the pyramid: rays may pass
        // beside it there.
        if (!(rays[4].distance(t.a) > 0.0 && rays[4].distance(t.b) > 0.0 &&
              rays[4].distance(t.c) > 0.0)) {
          Polygon3 sides{t.a, t.b, t.c};
          for (size_t i = 0; i < 4; ++i) sides = clip(sides, rays[i]);
          for (const glm::dvec3& x : sides)
            if (!(rays[4].distance(x) > 0.0)) return false;
        }
        const int own = faces(t);
        const std::array<glm::dvec3, 3> v{t.a, t.b, t.c};
        for (size_t k = 0; k < 3; ++k) {
          const uint32_t across = t.neighbour[k];
          if (own != 0 && across != kNoNeighbour && faces(casters_.triangles()[across]) == own)
            continue;
          if (segment_meets(v[k], v[(k + 1) % 3], wider.planes))
            return false;  // a silhouette edge inside
        }
        return true;
      });
}

}  // namespace sb::reference
