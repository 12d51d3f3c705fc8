#include "reference/exact_visibility.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <clipper.hpp>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <numeric>
#include <optional>
#include <tuple>
#include <type_traits>
#include <utility>

#include "reference/ray_offset.h"

namespace sb::reference {
namespace {

using Polygon3 = std::vector<glm::dvec3>;

struct Plane {
  glm::dvec3 normal;  // inside: dot(normal, x - point) >= 0
  glm::dvec3 point;
  double distance(const glm::dvec3& x) const { return glm::dot(normal, x - point); }
};

// Sutherland–Hodgman against one plane, keeping the inside: the n corners
// of `in` to `out` (room for 2n), returning how many it keeps.
size_t clip_into(const glm::dvec3* in, size_t n, const Plane& plane, glm::dvec3* out) {
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

Polygon3 clip(const Polygon3& in, const Plane& plane) {
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

// Whether any part of segment pq lies inside all five planes (parametric
// clipping: the part left is t in [t0, t1]).
bool segment_meets(const glm::dvec3& p, const glm::dvec3& q, const std::array<Plane, 5>& planes) {
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

// The light's frame: centre, unit axes along half_u and half_v, the unit
// normal, and the half sizes.
struct Frame {
  glm::dvec3 centre, u, v, normal;
  double hw = 0.0, hh = 0.0;
  explicit Frame(const AreaLight& l)
      : centre(l.center),
        hw(glm::length(glm::dvec3(l.half_u))),
        hh(glm::length(glm::dvec3(l.half_v))) {
    u = hw > 0.0 ? glm::dvec3(l.half_u) / hw : glm::dvec3(1, 0, 0);
    v = hh > 0.0 ? glm::dvec3(l.half_v) / hh : glm::dvec3(0, 0, 1);
    normal = glm::normalize(glm::cross(u, v));
  }
  std::array<glm::dvec3, 4> corners() const {
    const glm::dvec3 a = hw * u, b = hh * v;
    return {centre - a - b, centre + a - b, centre + a + b, centre - a + b};
  }
  glm::dvec2 plane_coords(const glm::dvec3& x) const {
    const glm::dvec3 d = x - centre;
    return {glm::dot(d, u), glm::dot(d, v)};
  }
};

// The pyramid from p to the light: four sides and the light's plane.
std::array<Plane, 5> pyramid(const Frame& f, const glm::dvec3& p) {
  const auto corners = f.corners();
  std::array<Plane, 5> planes;
  for (int i = 0; i < 4; ++i) {
    glm::dvec3 m = glm::cross(corners[size_t(i)] - p, corners[size_t((i + 1) % 4)] - p);
    if (glm::dot(m, f.centre - p) < 0.0) m = -m;
    planes[size_t(i)] = {m, p};
  }
  const double side = glm::dot(p - f.centre, f.normal) >= 0.0 ? 1.0 : -1.0;
  planes[4] = {side * f.normal, f.centre};
  return planes;
}

// Where the segment o + s·d, s in (0, 1], crosses triangle abc (Möller and
// Trumbore 1997): s, or +inf when it does not.
double segment_crossing(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a,
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

bool box_outside(const glm::dvec3& lo, const glm::dvec3& hi, const Plane& plane) {
  const glm::dvec3 far(plane.normal.x >= 0.0 ? hi.x : lo.x, plane.normal.y >= 0.0 ? hi.y : lo.y,
                       plane.normal.z >= 0.0 ? hi.z : lo.z);
  return plane.distance(far) < 0.0;
}

// Whether the box may meet the pyramid: it is outside none of its planes.
bool box_meets(const glm::dvec3& lo, const glm::dvec3& hi, const std::array<Plane, 5>& planes) {
  for (const Plane& plane : planes)
    if (box_outside(lo, hi, plane)) return false;
  return true;
}

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
  if (light.is_segment()) return std::nullopt;
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

constexpr double kIntegerRange = 1073741824.0;  // 2^30: the light's larger half-size

// Whether the segment o + t·d, t in [0, 1], meets the box (slab test).
bool segment_meets_box(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& lo,
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

// The part [t0, t1] of the segment x0 → x1 inside every plane; t0 > t1 when
// none is.
glm::dvec2 clip_segment(const glm::dvec3& x0, const glm::dvec3& x1,
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
bool below(double h0, double h1, glm::dvec2& interval) {
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

// A unit vector perpendicular to the unit vector d.
glm::dvec3 any_perpendicular(const glm::dvec3& d) {
  const glm::dvec3 axis = std::fabs(d.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(d, axis));
}

// The light (a rectangle or a segment) grown by a hair, 1e-6 of its size,
// on every side, as the six planes of a box facing in.
std::array<Plane, 6> light_box(const AreaLight& l) {
  const glm::dvec3 centre(l.center), half_u(l.half_u), half_v(l.half_v);
  const double lu = glm::length(half_u), lv = glm::length(half_v);
  glm::dvec3 u = lu > 0.0 ? half_u / lu : glm::dvec3(1, 0, 0);
  glm::dvec3 v = lv > 0.0 ? half_v / lv : any_perpendicular(u);
  if (!(lu > 0.0) && lv > 0.0) u = any_perpendicular(v);
  const glm::dvec3 n = glm::normalize(glm::cross(u, v));
  const double hair = 1e-6 * std::max(lu, lv);
  std::array<Plane, 6> box;
  size_t i = 0;
  for (const auto& [axis, half] : {std::pair{u, lu + hair}, {v, lv + hair}, {n, hair}}) {
    box[i++] = {axis, centre - half * axis};
    box[i++] = {-axis, centre + half * axis};
  }
  return box;
}

// The closed parts' crossings of the segment from a point p to the light's
// centre, to tell whether some part winds around p more often than around
// the centre: then every ray from p to the light crosses it (no closed
// part touches the light, so all of the light lies where the centre does)
// and p is in its umbra. Otherwise a ray that crosses a part crosses one
// of its triangles that faces p, whichever way the part winds: were every
// crossing along the normal, the winding number at the light would be
// lower than at p. Per part, crossings within 1e-9 of the segment's length
// of each other are one crossing when they agree in direction (the segment
// passes through an edge or a vertex, found in every triangle there) and
// none when they do not (it grazes the part). The leaving ones count +1,
// the entering ones -1, and the part winds around p more when the sum is
// positive. Crossings of different parts never merge: two parts touching
// face to face are crossed twice.
class PartCrossings {
 public:
  PartCrossings(const glm::dvec3& from, const glm::dvec3& to_centre)
      : from_(from), to_centre_(to_centre), crossings_(scratch()) {
    crossings_.clear();
  }
  PartCrossings(const PartCrossings&) = delete;
  PartCrossings& operator=(const PartCrossings&) = delete;

  // Notes where the segment crosses triangle abc (normal its winding's,
  // `outward` its part's orientation) of closed part `part`; returns where
  // along the segment, or +inf.
  double add(uint32_t part, int outward, const glm::dvec3& a, const glm::dvec3& b,
             const glm::dvec3& c, const glm::dvec3& normal) {
    const double s = segment_crossing(from_, to_centre_, a, b, c);
    if (s <= 1.0)
      crossings_.push_back({part, s, double(outward) * glm::dot(normal, to_centre_) > 0.0});
    return s;
  }

  // Whether some part winds around the segment's start more often than
  // around its end.
  bool winds_around_start() {
    constexpr double kSameCrossing = 1e-9;
    std::sort(crossings_.begin(), crossings_.end(), [](const Crossing& x, const Crossing& y) {
      return std::tie(x.part, x.s) < std::tie(y.part, y.s);
    });
    for (size_t i = 0; i < crossings_.size();) {
      const uint32_t part = crossings_[i].part;
      int leaving_minus_entering = 0;
      while (i < crossings_.size() && crossings_[i].part == part) {
        bool all_leave = true, all_enter = true;
        double last = crossings_[i].s;
        for (; i < crossings_.size() && crossings_[i].part == part &&
               crossings_[i].s - last <= kSameCrossing;
             ++i) {
          all_leave = all_leave && crossings_[i].leaves;
          all_enter = all_enter && !crossings_[i].leaves;
          last = crossings_[i].s;
        }
        leaving_minus_entering += all_leave ? 1 : all_enter ? -1 : 0;
      }
      if (leaving_minus_entering > 0) return true;
    }
    return false;
  }

 private:
  struct Crossing {
    uint32_t part;
    double s;
    bool leaves;  // along the part's outward normal
  };
  // One per thread, kept: a query per pixel would otherwise allocate.
  static std::vector<Crossing>& scratch() {
    thread_local std::vector<Crossing> crossings;
    return crossings;
  }
  glm::dvec3 from_, to_centre_;
  std::vector<Crossing>& crossings_;
};

}  // namespace

std::string ExactVisibility::unsupported_reason(const Scene& scene) {
  // A segment has an exact form (hidden_intervals); a point's V is 0 or 1.
  if (scene.light.is_point())
    return "the light has no area (the Monte Carlo reference is exact there)";
  for (const Mesh& mesh : scene.meshes) {
    if (!mesh.casts_shadow) continue;
    if (mesh.alpha_tested())
      return "caster mesh '" + mesh.name +
             "' is alpha-masked: its mask has no exact polygonal form here";
    if (mesh.analytic.kind != AnalyticShape::Kind::None)
      return "caster mesh '" + mesh.name +
             "' occludes as an analytic shape, which has no polygonal form";
  }
  return "";
}

ExactVisibility::ExactVisibility(const Scene& scene, const std::vector<bool>& closed)
    : light_(scene.light), unsupported_(unsupported_reason(scene)) {
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    if (!mesh.casts_shadow) continue;
    const bool is_closed = m < closed.size() && closed[m] && !mesh.double_sided;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      Triangle t{glm::dvec3(mesh.positions[mesh.indices[i]]),
                 glm::dvec3(mesh.positions[mesh.indices[i + 1]]),
                 glm::dvec3(mesh.positions[mesh.indices[i + 2]])};
      t.mesh = uint32_t(m);
      t.normal = glm::cross(t.b - t.a, t.c - t.a);
      t.outward = is_closed ? 1 : 0;  // closed; find_parts() orients it
      triangles_.push_back(t);
    }
  }
  if (!triangles_.empty()) build(0, uint32_t(triangles_.size()));
  link_neighbours();
  find_parts();
}

void ExactVisibility::find_parts() {
  const std::array<Plane, 6> light = light_box(light_);
  std::vector<uint32_t> part_triangles;
  uint32_t parts = 0;
  for (uint32_t seed = 0; seed < triangles_.size(); ++seed) {
    if (triangles_[seed].outward == 0 || triangles_[seed].part != kNoPart) continue;
    // Every triangle reached through shared edges (each closed caster's
    // edge has exactly two).
    const uint32_t part = parts++;
    triangles_[seed].part = part;
    part_triangles.assign(1, seed);
    // Six times the signed volume, about a corner of the part's own (its
    // rounding scales with the part's size, not with its distance).
    const glm::dvec3 origin = triangles_[seed].a;
    double volume = 0.0;
    bool touches_light = false;
    for (size_t q = 0; q < part_triangles.size(); ++q) {
      const Triangle& t = triangles_[part_triangles[q]];
      volume += glm::dot(t.a - origin, glm::cross(t.b - origin, t.c - origin));
      touches_light = touches_light || triangle_meets(t.a, t.b, t.c, light);
      for (const uint32_t across : t.neighbour)
        if (across != kNoNeighbour && triangles_[across].part == kNoPart) {
          triangles_[across].part = part;
          part_triangles.push_back(across);
        }
    }
    // A part the light touches winds differently around its points: it
    // keeps every triangle, as an open caster does.
    const int outward = touches_light ? 0 : volume < 0.0 ? -1 : 1;
    for (const uint32_t i : part_triangles) {
      triangles_[i].outward = outward;
      if (touches_light) triangles_[i].part = kNoPart;
    }
  }
}

void ExactVisibility::link_neighbours() {
  struct Edge {
    uint32_t mesh;
    std::array<double, 6> ends;  // the lesser end first
    uint32_t triangle;
    int k;
    bool operator<(const Edge& o) const { return std::tie(mesh, ends) < std::tie(o.mesh, o.ends); }
    bool same(const Edge& o) const { return mesh == o.mesh && ends == o.ends; }
  };
  std::vector<Edge> edges;
  for (uint32_t i = 0; i < triangles_.size(); ++i) {
    const Triangle& t = triangles_[i];
    if (t.outward == 0) continue;
    const std::array<glm::dvec3, 3> v{t.a, t.b, t.c};
    for (int k = 0; k < 3; ++k) {
      glm::dvec3 p = v[size_t(k)], q = v[size_t((k + 1) % 3)];
      if (std::tie(q.x, q.y, q.z) < std::tie(p.x, p.y, p.z)) std::swap(p, q);
      edges.push_back({t.mesh, {p.x, p.y, p.z, q.x, q.y, q.z}, i, k});
    }
  }
  std::sort(edges.begin(), edges.end());
  for (size_t e = 0; e < edges.size();) {
    size_t end = e + 1;
    while (end < edges.size() && edges[end].same(edges[e])) ++end;
    if (end - e == 2) {  // exactly two triangles share it
      triangles_[edges[e].triangle].neighbour[size_t(edges[e].k)] = edges[e + 1].triangle;
      triangles_[edges[e + 1].triangle].neighbour[size_t(edges[e + 1].k)] = edges[e].triangle;
    }
    e = end;
  }
}

ExactVisibility::~ExactVisibility() = default;

uint32_t ExactVisibility::build(uint32_t first, uint32_t count) {
  Node node;
  node.lo = glm::dvec3(1e300);
  node.hi = glm::dvec3(-1e300);
  for (uint32_t i = first; i < first + count; ++i)
    for (const glm::dvec3& x : {triangles_[i].a, triangles_[i].b, triangles_[i].c}) {
      node.lo = glm::min(node.lo, x);
      node.hi = glm::max(node.hi, x);
    }
  const auto index = uint32_t(nodes_.size());
  nodes_.push_back(node);
  if (count <= 4) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  const glm::dvec3 extent = node.hi - node.lo;
  const int axis =
      extent.x > extent.y ? (extent.x > extent.z ? 0 : 2) : (extent.y > extent.z ? 1 : 2);
  const auto centroid = [axis](const Triangle& t) { return t.a[axis] + t.b[axis] + t.c[axis]; };
  const uint32_t half = count / 2;
  std::nth_element(triangles_.begin() + first, triangles_.begin() + first + half,
                   triangles_.begin() + first + count,
                   [&](const Triangle& x, const Triangle& y) { return centroid(x) < centroid(y); });
  const uint32_t left = build(first, half);
  const uint32_t right = build(first + half, count - half);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

template <typename Keep, typename Visit>
bool ExactVisibility::traverse(const Keep& keep, const Visit& visit) const {
  if (nodes_.empty()) return true;
  // One per thread, kept: a walk per pixel would otherwise allocate.
  thread_local std::vector<uint32_t> stack;
  stack.assign(1, 0);
  while (!stack.empty()) {
    const Node& node = nodes_[stack.back()];
    stack.pop_back();
    if (!keep(node.lo, node.hi)) continue;
    if (node.count == 0) {
      stack.push_back(node.left);
      stack.push_back(node.right);
      continue;
    }
    for (uint32_t i = node.first; i < node.first + node.count; ++i) {
      if constexpr (std::is_void_v<std::invoke_result_t<const Visit&, const Triangle&>>)
        visit(triangles_[i]);
      else if (!visit(triangles_[i]))
        return false;
    }
  }
  return true;
}

glm::dvec3 ExactVisibility::viewpoint(const glm::dvec3& surface, const glm::dvec3& n) const {
  // The caster triangles the surface point lies on, by the Monte Carlo
  // reference's own test (ray_offset.h).
  const double radius = detail::offset_radius(surface);
  double largest = 0.0;
  traverse(
      [&](const glm::dvec3& lo, const glm::dvec3& hi) {
        const glm::dvec3 outside = glm::max(lo - surface, glm::max(surface - hi, glm::dvec3(0.0)));
        return glm::dot(outside, outside) <= radius * radius;
      },
      [&](const Triangle& t) {
        largest = std::max(largest, detail::lies_on_scale(surface, radius, t.a, t.b, t.c));
      });
  // Along the unit normal, as the Monte Carlo rays start.
  const double length = glm::length(n);
  return length > 0.0 ? surface + detail::offset_from(surface, largest) / length * n : surface;
}

std::vector<glm::dvec2> ExactVisibility::hidden_intervals(const glm::dvec3& surface,
                                                          const glm::dvec3& n) const {
  std::vector<glm::dvec2> out;
  const glm::dvec3 a_end(light_.segment_end(0.0f)), b_end(light_.segment_end(1.0f));
  glm::dvec2 interval;
  // The horizon: the part of the segment below the tangent plane.
  if (below(glm::dot(n, a_end - surface), glm::dot(n, b_end - surface), interval))
    out.push_back(interval);
  if (nodes_.empty()) return out;
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
  const auto candidate = [&](const Triangle& t) {
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
    traverse(
        [&](const glm::dvec3& lo, const glm::dvec3& hi) {
          return (xa < 0.0 && segment_meets_box(p, a, lo, hi)) ||
                 (xb > 0.0 && segment_meets_box(p, b, lo, hi)) ||
                 segment_meets_box(p, to_centre, lo, hi);
        },
        [&](const Triangle& t) {
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
  traverse(
      [&](const glm::dvec3& lo, const glm::dvec3& hi) {
        for (const Plane& plane : planes)
          if (box_outside(lo, hi, plane)) return false;
        return true;
      },
      [&](const Triangle& t) {
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

std::vector<std::vector<glm::dvec2>> ExactVisibility::occluding_polygons(
    const glm::dvec3& surface, const glm::dvec3& n) const {
  std::vector<std::vector<glm::dvec2>> out;
  const Frame f(light_);
  // The light below the tangent plane through the surface point.
  const auto corners = f.corners();
  const Polygon3 below = clip(Polygon3(corners.begin(), corners.end()), Plane{-n, surface});
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
  const auto planes = pyramid(f, p);
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
  if (zp == 0.0 || nodes_.empty()) return out;
  // Triangles whose plane passes this close to p contain it, as seen from
  // p: their projection has no area.
  const double on_plane = 1e-12 * std::max(glm::length(p), 1.0);
  // Whether p is inside a closed part that the light is outside of
  // (PartCrossings), by the segment from p to the light's centre. It lies
  // in the pyramid, so every triangle it can cross is visited.
  const glm::dvec3 to_centre = f.centre - p;
  PartCrossings crossings(p, to_centre);
  traverse([&](const glm::dvec3& lo, const glm::dvec3& hi) { return box_meets(lo, hi, planes); },
           [&](const Triangle& t) {
             const glm::dvec3& normal = t.normal;
             const double facing = glm::dot(normal, p - t.a);
             if (t.part != kNoPart) crossings.add(t.part, t.outward, t.a, t.b, t.c, normal);
             if (std::fabs(facing) <= on_plane * glm::length(normal)) return;
             if (double(t.outward) * facing < 0.0) return;  // a closed caster's far side
             if (glm::dot(n, t.a - surface) < 0.0 && glm::dot(n, t.b - surface) < 0.0 &&
                 glm::dot(n, t.c - surface) < 0.0)
               return;  // below the tangent plane: inside the horizon polygon
             Polygon3 poly{t.a, t.b, t.c};
             for (const Plane& plane : planes) poly = clip(poly, plane);
             add(clip(poly, tangent), true);
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
  return traverse([&](const glm::dvec3& lo, const glm::dvec3& hi) { return rays.meets(lo, hi); },
                  [&](const Triangle& t) { return !triangle_meets(t.a, t.b, t.c, rays.planes); });
}

bool ExactVisibility::hides_whole_light(const glm::dvec3& surface, const glm::dvec3& origin,
                                        const glm::dvec3& n) const {
  // The horizon: the Monte Carlo rays trace no sample below the origin's
  // plane. All of the light below it hides all of it; part of it, nothing
  // this proves.
  const std::optional<ProofStart> start = proof_start(light_, surface, origin, n);
  if (!start) return false;
  if (start->below == 4) return true;
  if (start->above != 4 || nodes_.empty()) return false;
  const Frame& f = start->light;
  const double offset = start->offset;
  // The closed part the ray to the light's centre crosses first.
  const glm::dvec3 to_centre = f.centre - origin;
  PartCrossings crossings(origin, to_centre);
  double first_hit = std::numeric_limits<double>::infinity();
  const Triangle* first = nullptr;
  traverse([&](const glm::dvec3& lo,
               const glm::dvec3& hi) { return segment_meets_box(origin, to_centre, lo, hi); },
           [&](const Triangle& t) {
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
  const auto faces = [&](const Triangle& t) {
    const double facing = glm::dot(t.normal, origin - t.a);
    return facing > 0.0 ? 1 : facing < 0.0 ? -1 : 0;
  };
  return traverse([&](const glm::dvec3& lo, const glm::dvec3& hi) { return wider.meets(lo, hi); },
                  [&](const Triangle& t) {
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
                      if (own != 0 && across != kNoNeighbour && faces(triangles_[across]) == own)
                        continue;
                      if (segment_meets(v[k], v[(k + 1) % 3], wider.planes))
                        return false;  // a silhouette edge inside
                    }
                    return true;
                  });
}

double ExactVisibility::visibility(const glm::dvec3& p, const glm::dvec3& n) const {
  if (light_.is_segment()) return std::clamp(1.0 - union_length(hidden_intervals(p, n)), 0.0, 1.0);
  const Frame f(light_);
  const auto polygons = occluding_polygons(p, n);
  if (polygons.empty()) return 1.0;
  return std::clamp(1.0 - union_area(polygons, f.hw, f.hh) / (4.0 * f.hw * f.hh), 0.0, 1.0);
}

ImageF ExactVisibility::image(const ImageF& positions, const ImageF& normals) const {
  ImageF out(positions.width, positions.height, 1, 1.0f);
  tbb::parallel_for(0, positions.height, [&](int y) {
    for (int x = 0; x < positions.width; ++x) {
      const size_t i = size_t(y) * size_t(positions.width) + size_t(x);
      const float* pos = &positions.data[i * 4];
      if (!(pos[3] > 0.5f)) continue;
      const float* nor = &normals.data[i * size_t(normals.channels)];
      out.data[i] =
          float(visibility(glm::dvec3(pos[0], pos[1], pos[2]), glm::dvec3(nor[0], nor[1], nor[2])));
    }
  });
  return out;
}

}  // namespace sb::reference
