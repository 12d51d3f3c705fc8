// The adaptive reference's proofs (exact_visibility.h: sees_whole_light,
// hides_whole_light; adaptive.h): that every shadow ray from a point
// reaches the light, or that none does.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "reference/closed_parts.h"
#include "reference/exact_visibility.h"
#include "reference/light_frame.h"

namespace sb::reference {

using core::AreaLight;

namespace {

using detail::box_meets;
using detail::box_outside;
using detail::CasterBvh;
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

// The shaft of a set of ray origins (a pixel tile's), each as
// sees_whole_light takes it: six planes holding every origin's wider
// pyramid (proof_pyramid, from its apex set back), and their box. Its sides
// pass through the edges of the rectangle in the cap's plane that holds
// every pyramid's section there, each turned about its edge until every
// apex is inside; then the cap; then a plane below every apex along the
// first point's normal (so the flat surface they lie on stays outside),
// with the cap inside. Empty where one origin has no proof start, a light
// corner below its horizon, or where the origins lie on both sides of the
// light's plane or the cap reaches below the last plane.
struct Shaft {
  std::array<Plane, 6> planes;
  glm::dvec3 lo{0.0}, hi{0.0};
  Plane light_plane;                            // the light's own, facing the origins
  glm::dvec3 origins_lo{0.0}, origins_hi{0.0};  // the origins' box
  bool meets(const glm::dvec3& box_lo, const glm::dvec3& box_hi) const {
    if (box_lo.x > hi.x || box_lo.y > hi.y || box_lo.z > hi.z || lo.x > box_hi.x ||
        lo.y > box_hi.y || lo.z > box_hi.z)
      return false;
    for (const Plane& plane : planes)
      if (box_outside(box_lo, box_hi, plane)) return false;
    return true;
  }
};

std::optional<Shaft> tile_shaft(const AreaLight& light,
                                std::span<const ExactVisibility::ProofPoint> points) {
  if (points.empty()) return std::nullopt;
  std::vector<glm::dvec3> apexes;
  apexes.reserve(points.size());
  std::optional<Frame> wider;
  double side = 0.0;
  Shaft shaft;
  shaft.origins_lo = shaft.origins_hi = points[0].origin;
  for (const ExactVisibility::ProofPoint& q : points) {
    const std::optional<ProofStart> s = proof_start(light, q.surface, q.origin, q.n);
    if (!s || s->above != 4) return std::nullopt;
    const glm::dvec3 apex = q.origin - 0.25 * s->offset * s->axis;
    const double h = glm::dot(apex - s->light.centre, s->light.normal);
    const double sign = h > 0.0 ? 1.0 : h < 0.0 ? -1.0 : 0.0;
    if (sign == 0.0 || (side != 0.0 && sign != side)) return std::nullopt;
    side = sign;
    if (!wider) wider = s->light;
    apexes.push_back(apex);
    shaft.origins_lo = glm::min(shaft.origins_lo, q.origin);
    shaft.origins_hi = glm::max(shaft.origins_hi, q.origin);
  }
  const Frame& f = *wider;
  const double size = std::max(f.hw, f.hh), beyond = kProofWider * size;
  // A hair against rounding: every plane below is moved out by it.
  const double hair = 1e-9 * size;
  const glm::dvec3 inward = side * f.normal;  // towards the apexes
  const glm::dvec3 cap_centre = f.centre - beyond * inward;
  double u0 = std::numeric_limits<double>::infinity(), v0 = u0, u1 = -u0, v1 = -u0;
  for (const glm::dvec3& apex : apexes) {
    const double depth = std::fabs(glm::dot(apex - f.centre, f.normal));
    const double scale = (depth + beyond) / depth;
    for (const glm::dvec3& corner : f.corners()) {
      const glm::dvec2 c = f.plane_coords(apex + (corner - apex) * scale);
      u0 = std::min(u0, c.x);
      u1 = std::max(u1, c.x);
      v0 = std::min(v0, c.y);
      v1 = std::max(v1, c.y);
    }
  }
  u0 -= hair;
  v0 -= hair;
  u1 += hair;
  v1 += hair;
  const std::array<glm::dvec3, 4> cap{
      cap_centre + u0 * f.u + v0 * f.v, cap_centre + u1 * f.u + v0 * f.v,
      cap_centre + u1 * f.u + v1 * f.v, cap_centre + u0 * f.u + v1 * f.v};
  // A plane holding every apex: moved out past the one farthest outside
  // (for the sides, none but by rounding) and a hair more.
  const auto holding_all = [&](glm::dvec3 normal, const glm::dvec3& point) {
    normal = glm::normalize(normal);
    double worst = 0.0;
    for (const glm::dvec3& apex : apexes) worst = std::min(worst, glm::dot(normal, apex - point));
    return Plane{normal, point - (hair - worst) * normal};
  };
  // The apexes lie on one side of the cap's plane, so each one outside a
  // side turns it further the same way about its edge: the last is the
  // support.
  for (size_t k = 0; k < 4; ++k) {
    const glm::dvec3 &a = cap[k], &b = cap[(k + 1) % 4];
    glm::dvec3 normal(0.0);
    for (size_t j = 0; j < apexes.size(); ++j) {
      if (j > 0 && glm::dot(normal, apexes[j] - a) >= 0.0) continue;
      normal = glm::cross(b - a, apexes[j] - a);
      if (glm::dot(normal, cap_centre - a) < 0.0) normal = -normal;
    }
    if (!(glm::length(normal) > 0.0)) return std::nullopt;
    shaft.planes[k] = holding_all(normal, a);
  }
  shaft.planes[4] = Plane{inward, cap_centre};
  shaft.planes[5] = holding_all(points[0].n, apexes[0]);
  for (const glm::dvec3& corner : cap)
    if (shaft.planes[5].distance(corner) < 0.0) return std::nullopt;
  shaft.light_plane = Plane{inward, f.centre};
  shaft.lo = shaft.hi = apexes[0];
  for (const glm::dvec3& x : apexes) {
    shaft.lo = glm::min(shaft.lo, x);
    shaft.hi = glm::max(shaft.hi, x);
  }
  for (const glm::dvec3& x : cap) {
    shaft.lo = glm::min(shaft.lo, x);
    shaft.hi = glm::max(shaft.hi, x);
  }
  return shaft;
}

// Which side of triangle t's plane every point of the box lies on: +1 the
// side its normal points to, -1 the other, 0 both, on it or near it.
int side_of_box(const CasterTriangle& t, const glm::dvec3& lo, const glm::dvec3& hi) {
  const glm::dvec3 centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  const double d = glm::dot(t.normal, centre - t.a), r = glm::dot(glm::abs(t.normal), half);
  // A margin far beyond the rounding of the facing test at one point
  // (keeps_umbra), so that every point in the box gets this answer there.
  const auto l1 = [](const glm::dvec3& x) {
    return std::fabs(x.x) + std::fabs(x.y) + std::fabs(x.z);
  };
  const double margin = 1e-9 * l1(t.normal) * (l1(centre - t.a) + l1(half));
  return d > r + margin ? 1 : d < -r - margin ? -1 : 0;
}

// The first closed part that the segment from origin to centre crosses
// (nullptr: none); `inside` when some part winds around origin more often
// than around centre (closed_parts.h).
const CasterTriangle* first_part(const CasterBvh& casters, const glm::dvec3& origin,
                                 const glm::dvec3& centre, bool& inside) {
  const glm::dvec3 to_centre = centre - origin;
  PartCrossings crossings(origin, to_centre);
  double first_hit = std::numeric_limits<double>::infinity();
  const CasterTriangle* first = nullptr;
  casters.traverse(
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
  inside = first != nullptr && crossings.winds_around_start();
  return first;
}

// Whether triangle t of the part keeps hides_whole_light's proof from
// origin: it does not reach the light's plane inside `rays`, and none of
// its edges that is a silhouette seen from origin (an edge-on triangle, or
// no single neighbour, counting as one) meets `wider`.
bool keeps_umbra(const std::vector<CasterTriangle>& all, const CasterTriangle& t,
                 const glm::dvec3& origin, const std::array<Plane, 5>& rays,
                 const std::array<Plane, 5>& wider) {
  // Reaching the light's plane inside the pyramid: rays may pass beside it
  // there.
  if (!(rays[4].distance(t.a) > 0.0 && rays[4].distance(t.b) > 0.0 &&
        rays[4].distance(t.c) > 0.0)) {
    Polygon3 sides{t.a, t.b, t.c};
    for (size_t i = 0; i < 4; ++i) sides = clip(sides, rays[i]);
    for (const glm::dvec3& x : sides)
      if (!(rays[4].distance(x) > 0.0)) return false;
  }
  const auto faces = [&](const CasterTriangle& u) {
    const double facing = glm::dot(u.normal, origin - u.a);
    return facing > 0.0 ? 1 : facing < 0.0 ? -1 : 0;
  };
  const int own = faces(t);
  const std::array<glm::dvec3, 3> v{t.a, t.b, t.c};
  for (size_t k = 0; k < 3; ++k) {
    const uint32_t across = t.neighbour[k];
    if (own != 0 && across != kNoNeighbour && faces(all[across]) == own) continue;
    if (segment_meets(v[k], v[(k + 1) % 3], wider)) return false;  // a silhouette edge inside
  }
  return true;
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
  return hides_whole_light({surface, origin, n}, TileCandidates{});
}

bool ExactVisibility::hides_whole_light(const ProofPoint& q, const TileCandidates& dark) const {
  // The horizon: the Monte Carlo rays trace no sample below the origin's
  // plane. All of the light below it hides all of it; part of it, nothing
  // this proves.
  const glm::dvec3& origin = q.origin;
  const std::optional<ProofStart> start = proof_start(light_, q.surface, origin, q.n);
  if (!start) return false;
  if (start->below == 4) return true;
  if (start->above != 4 || casters_.empty()) return false;
  // The closed part the ray to the light's centre crosses first.
  bool inside = false;
  const CasterTriangle* first = first_part(casters_, origin, start->light.centre, inside);
  if (first == nullptr) return false;
  // Inside a closed part: every ray leaves it (as the exact visibility has it).
  if (inside) return true;
  // That part alone (a closed surface), whichever way it winds.
  const uint32_t part = first->part;
  const std::array<Plane, 5> rays = proof_pyramid(*start, origin).planes;
  const ProofPyramid wider = proof_pyramid(*start, origin - 0.25 * start->offset * start->axis);
  const auto keeps = [&](const CasterTriangle& t) {
    return keeps_umbra(casters_.triangles(), t, origin, rays, wider.planes);
  };
  if (dark.usable && dark.part == part) {
    // The tile's walk found every triangle of the part that could fail.
    for (const uint32_t i : dark.triangles)
      if (!keeps(casters_.triangles()[i])) return false;
    return true;
  }
  return casters_.traverse(
      [&](const glm::dvec3& lo, const glm::dvec3& hi) { return wider.meets(lo, hi); },
      [&](const CasterTriangle& t) { return t.part != part || keeps(t); });
}

bool ExactVisibility::sees_whole_light(const ProofPoint& q, const TileCandidates& lit) const {
  if (!lit.usable) return sees_whole_light(q.surface, q.origin, q.n);
  const std::optional<ProofStart> start = proof_start(light_, q.surface, q.origin, q.n);
  if (!start || start->above != 4) return false;
  const ProofPyramid rays = proof_pyramid(*start, q.origin - 0.25 * start->offset * start->axis);
  // The tile's walk found every triangle that could meet the pyramid.
  for (const uint32_t i : lit.triangles) {
    const CasterTriangle& t = casters_.triangles()[i];
    // Outside the pyramid's box: the cheap answer for most.
    const glm::dvec3 lo = glm::min(t.a, glm::min(t.b, t.c)), hi = glm::max(t.a, glm::max(t.b, t.c));
    if (hi.x < rays.lo.x || hi.y < rays.lo.y || hi.z < rays.lo.z || lo.x > rays.hi.x ||
        lo.y > rays.hi.y || lo.z > rays.hi.z)
      continue;
    if (triangle_meets(t.a, t.b, t.c, rays.planes)) return false;
  }
  return true;
}

void ExactVisibility::sees_candidates(std::span<const ProofPoint> points,
                                      TileCandidates& out) const {
  out = {};
  const std::optional<Shaft> shaft = tile_shaft(light_, points);
  if (!shaft) return;
  // Every triangle not wholly outside one of the shaft's planes: any that
  // meets a point's pyramid is one of them. Clipped exactly only while the
  // list is empty (whether the tile is whole); after that, the points'
  // own tests reject the others.
  const CasterTriangle* const base = casters_.triangles().data();
  out.usable = casters_.traverse(
      [&](const glm::dvec3& lo, const glm::dvec3& hi) { return shaft->meets(lo, hi); },
      [&](const CasterTriangle& t) {
        for (const Plane& plane : shaft->planes)
          if (plane.distance(t.a) < 0.0 && plane.distance(t.b) < 0.0 && plane.distance(t.c) < 0.0)
            return true;
        if (out.triangles.empty() && !triangle_meets(t.a, t.b, t.c, shaft->planes)) return true;
        if (out.triangles.size() == kMaxCandidates) return false;
        out.triangles.push_back(uint32_t(&t - base));
        return true;
      });
  out.whole = out.usable && out.triangles.empty();
  if (!out.usable) out.triangles.clear();
}

void ExactVisibility::hides_candidates(std::span<const ProofPoint> points,
                                       TileCandidates& out) const {
  out = {};
  if (points.empty()) return;
  // The horizon: all of the light below every point's plane.
  bool all_below = true;
  for (const ProofPoint& q : points) {
    const std::optional<ProofStart> s = proof_start(light_, q.surface, q.origin, q.n);
    if (!s) return;
    all_below = all_below && s->below == 4;
  }
  if (all_below) {
    out.usable = out.whole = true;
    out.part = kNoPart;
    return;
  }
  if (casters_.empty()) return;
  const std::optional<Shaft> shaft = tile_shaft(light_, points);
  if (!shaft) return;
  bool inside = false;
  const CasterTriangle* first =
      first_part(casters_, points[0].origin, glm::dvec3(light_.center), inside);
  if (first == nullptr || inside) return;
  out.part = first->part;
  // The part's triangles that could fail keeps_umbra for some point: one
  // with a point not in front of the light's plane, or an edge inside the
  // shaft between triangles that do not both face the origins' box the
  // same way (or with no neighbour). The others keep it at every point.
  const Shaft& sh = *shaft;
  const std::vector<CasterTriangle>& all = casters_.triangles();
  bool meets_origins = false;
  out.usable = casters_.traverse(
      [&](const glm::dvec3& lo, const glm::dvec3& hi) { return sh.meets(lo, hi); },
      [&](const CasterTriangle& t) {
        if (t.part != out.part) return true;
        bool suspect = !(sh.light_plane.distance(t.a) > 0.0 && sh.light_plane.distance(t.b) > 0.0 &&
                         sh.light_plane.distance(t.c) > 0.0);
        const int own = side_of_box(t, sh.origins_lo, sh.origins_hi);
        if (own == 0 && !meets_origins) meets_origins = triangle_meets(t.a, t.b, t.c, sh.planes);
        const std::array<glm::dvec3, 3> v{t.a, t.b, t.c};
        for (size_t k = 0; k < 3 && !suspect; ++k) {
          const uint32_t across = t.neighbour[k];
          if (own != 0 && across != kNoNeighbour &&
              side_of_box(all[across], sh.origins_lo, sh.origins_hi) == own)
            continue;
          suspect = segment_meets(v[k], v[(k + 1) % 3], sh.planes);
        }
        if (!suspect) return true;
        if (out.triangles.size() == kMaxCandidates) return false;
        out.triangles.push_back(uint32_t(&t - all.data()));
        return true;
      });
  if (!out.usable) {
    out.triangles.clear();
    return;
  }
  // Then whether a ray from a point to the light crosses the part changes
  // only where it grazes a silhouette edge from its point, meets the part
  // in the light's plane, or starts on the part: with no candidate, and
  // no triangle whose plane meets the origins' box inside the shaft, every
  // ray crosses it as the first point's ray to the centre does.
  out.whole = out.triangles.empty() && !meets_origins;
}

}  // namespace sb::reference
