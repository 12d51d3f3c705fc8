#include "penumbra_wedge/wedge_geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <utility>

namespace sb::techniques::penumbra_wedge {

using core::Bounds;

namespace {

float cross2(const glm::vec2& a, const glm::vec2& b) { return a.x * b.y - a.y * b.x; }

// Convex hull of `n` points, counter-clockwise, without collinear points
// (Andrew's monotone chain). Returns the hull's size.
int convex_hull(std::array<glm::vec2, 8>& pts, std::array<glm::vec2, 16>& hull) {
  std::sort(pts.begin(), pts.end(), [](const glm::vec2& p, const glm::vec2& q) {
    return p.x < q.x || (p.x == q.x && p.y < q.y);
  });
  int k = 0;
  for (const glm::vec2& p : pts) {  // lower chain
    while (k >= 2 && cross2(hull[k - 1] - hull[k - 2], p - hull[k - 2]) <= 0.0f) --k;
    hull[k++] = p;
  }
  for (int i = int(pts.size()) - 2, lower = k + 1; i >= 0; --i) {  // upper chain
    const glm::vec2& p = pts[size_t(i)];
    while (k >= lower && cross2(hull[k - 1] - hull[k - 2], p - hull[k - 2]) <= 0.0f) --k;
    hull[k++] = p;
  }
  return std::max(k - 1, 0);  // the last point repeats the first
}

// The plane through three world points, (n, −n·p0) with |n| = 1; zero when
// they are collinear.
glm::vec4 plane_through(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
  const glm::vec3 n = glm::cross(p1 - p0, p2 - p0);
  const float length = glm::length(n);
  if (!(length > 0.0f)) return glm::vec4(0.0f);
  return {n / length, -glm::dot(n / length, p0)};
}

// Where the segment p q meets the plane, computed from the lesser end so that
// both faces that share the edge get the bit-identical point.
glm::vec3 cut(glm::vec3 p, glm::vec3 q, const glm::vec4& plane) {
  if (std::tie(q.x, q.y, q.z) < std::tie(p.x, p.y, p.z)) std::swap(p, q);
  const float dp = glm::dot(glm::vec3(plane), p) + plane.w;
  const float dq = glm::dot(glm::vec3(plane), q) + plane.w;
  return p + (q - p) * (dp / (dp - dq));
}

// Cuts a convex polyhedron (faces wound outwards) to the side where `plane`
// is <= 0, closing it with the cut's polygon.
void clip_faces(std::vector<std::vector<glm::vec3>>& faces, const glm::vec4& plane,
                WedgeScratch& scratch) {
  auto& kept = scratch.kept;
  auto& rim = scratch.rim;
  kept.clear();
  rim.clear();
  const auto distance = [&](const glm::vec3& p) { return glm::dot(glm::vec3(plane), p) + plane.w; };
  for (const auto& face : faces) {
    std::vector<glm::vec3> part;
    for (size_t i = 0; i < face.size(); ++i) {
      const glm::vec3 &p = face[i], &q = face[(i + 1) % face.size()];
      const float dp = distance(p), dq = distance(q);
      if (dp <= 0.0f) part.push_back(p);
      if (dp == 0.0f) rim.push_back(p);
      if ((dp < 0.0f && dq > 0.0f) || (dp > 0.0f && dq < 0.0f)) {
        part.push_back(cut(p, q, plane));
        rim.push_back(part.back());
      }
    }
    if (part.size() >= 3) kept.push_back(std::move(part));
  }
  // The cut polygon: its points (each found by two faces) in order about
  // their centre, counter-clockwise seen from outside (along the normal).
  std::sort(rim.begin(), rim.end(), [](const glm::vec3& a, const glm::vec3& b) {
    return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
  });
  rim.erase(std::unique(rim.begin(), rim.end()), rim.end());
  if (rim.size() >= 3) {
    glm::vec3 centre(0.0f);
    for (const glm::vec3& p : rim) centre += p;
    centre /= float(rim.size());
    const glm::vec3 n(plane);
    const glm::vec3 u = glm::normalize(rim[0] - centre);
    const glm::vec3 v = glm::cross(n, u);
    std::sort(rim.begin(), rim.end(), [&](const glm::vec3& a, const glm::vec3& b) {
      return std::atan2(glm::dot(a - centre, v), glm::dot(a - centre, u)) <
             std::atan2(glm::dot(b - centre, v), glm::dot(b - centre, u));
    });
    kept.push_back(rim);
  }
  faces.swap(kept);
}

}  // namespace

WedgeRange wedge_range(const LightFrame& frame, const Bounds& scene) {
  WedgeRange r;
  r.far = std::max(frame.farthest(scene), 1e-6f);
  r.near = 1e-3f * r.far;
  // A margin, so that a surface on the box's face is inside the cut hull.
  const glm::vec3 margin(1e-3f * std::max(glm::length(scene.hi - scene.lo), 1e-6f));
  r.box.lo = scene.lo - margin;
  r.box.hi = scene.hi + margin;
  return r;
}

bool append_wedge(const LightFrame& frame, const glm::vec3& a, const glm::vec3& b,
                  const WedgeRange& range, WedgeBatch& out) {
  glm::vec3 A = frame.to_light(a), B = frame.to_light(b);
  // Keep the part of the edge with near <= z <= far.
  for (const auto& [limit, keep_above] :
       {std::pair{range.near, true}, std::pair{range.far, false}}) {
    const float da = keep_above ? A.z - limit : limit - A.z;
    const float db = keep_above ? B.z - limit : limit - B.z;
    if (da < 0.0f && db < 0.0f) return false;
    if (da < 0.0f) A = A + (B - A) * (da / (da - db));
    if (db < 0.0f) B = B + (A - B) * (db / (db - da));
  }
  if (glm::length(B - A) <= 1e-7f * range.far) return false;

  // The far cap in z = cap_z: the light seen through A and through B.
  const float cap_z = range.far * 1.01f + 1e-6f;
  const glm::vec2 half(frame.half_width, frame.half_height);
  std::array<glm::vec2, 8> corners{};
  for (int e = 0; e < 2; ++e) {
    const glm::vec3& end = e == 0 ? A : B;
    const float k = cap_z / end.z;
    const glm::vec2 centre = k * glm::vec2(end);
    const glm::vec2 h = (k - 1.0f) * half;
    for (int c = 0; c < 4; ++c)
      corners[(4 * size_t(e)) + size_t(c)] =
          centre + glm::vec2((c & 1) ? h.x : -h.x, (c & 2) ? h.y : -h.y);
  }
  std::array<glm::vec2, 16> cap{};
  const int m = convex_hull(corners, cap);
  if (m < 3) return false;

  // Hull vertices (light frame): the cap, then A and B.
  std::array<glm::vec3, 10> hull{};
  for (int i = 0; i < m; ++i) hull[size_t(i)] = glm::vec3(cap[size_t(i)], cap_z);
  const int ia = m, ib = m + 1;
  hull[size_t(ia)] = A;
  hull[size_t(ib)] = B;
  glm::vec3 interior(0.0f);
  for (int i = 0; i < m + 2; ++i) interior += hull[size_t(i)];
  interior /= float(m + 2);

  // The hull's faces, wound outwards, in world space.
  auto& faces = out.scratch.faces;
  faces.clear();
  const auto triangle = [&](int i0, int i1, int i2) {
    const glm::vec3 &p0 = hull[size_t(i0)], &p1 = hull[size_t(i1)], &p2 = hull[size_t(i2)];
    const glm::vec3 normal = glm::cross(p1 - p0, p2 - p0);
    const float outward = glm::dot(normal, p0 - interior);
    if (outward == 0.0f) return;  // degenerate (flat) triangle: covers no pixel
    if (outward < 0.0f) std::swap(i1, i2);
    faces.push_back({frame.to_world(hull[size_t(i0)]), frame.to_world(hull[size_t(i1)]),
                     frame.to_world(hull[size_t(i2)])});
  };
  for (int i = 1; i + 1 < m; ++i) triangle(0, i, i + 1);  // the far cap
  // Each cap edge closes with the apex (A or B) that the plane turning about
  // it from the cap meets first; where the choice changes at a cap vertex,
  // the triangle (vertex, A, B) lies between.
  std::array<int, 16> apex{};
  for (int j = 0; j < m; ++j) {
    const glm::vec2 c0 = cap[size_t(j)], c1 = cap[size_t((j + 1) % m)];
    const glm::vec2 edge = c1 - c0;
    const glm::vec2 outward = glm::vec2(edge.y, -edge.x) / glm::length(edge);
    const glm::vec2 sa(glm::dot(glm::vec2(A) - c0, outward), cap_z - A.z);
    const glm::vec2 sb(glm::dot(glm::vec2(B) - c0, outward), cap_z - B.z);
    apex[size_t(j)] = cross2(sa, sb) >= 0.0f ? ia : ib;
    triangle(j, (j + 1) % m, apex[size_t(j)]);
  }
  for (int j = 0; j < m; ++j)
    if (apex[size_t(j)] != apex[size_t((j + 1) % m)]) triangle((j + 1) % m, ia, ib);

  // Only the part inside the scene's box can hold a surface point: cut the
  // rest away, so that its pixels are not shaded for nothing.
  if (!range.box.empty()) {
    for (int axis = 0; axis < 3; ++axis)
      for (const float side : {-1.0f, 1.0f}) {
        glm::vec4 plane(0.0f);  // outside where positive
        plane[axis] = side;
        plane.w = side > 0.0f ? -range.box.hi[axis] : range.box.lo[axis];
        clip_faces(faces, plane, out.scratch);
      }
    if (faces.empty()) return false;
  }

  const auto index = uint32_t(out.wedges.size());
  for (const auto& face : faces)
    for (size_t i = 1; i + 1 < face.size(); ++i)
      for (const glm::vec3& p : {face[0], face[i], face[i + 1]}) {
        out.indices.push_back(uint32_t(out.vertices.size()));
        out.vertices.push_back({p, index});
      }

  // Lengyel's planes: the light corners' angles about the edge, from the
  // light's centre.
  WedgeRecord w;
  w.a = glm::vec4(A, 0.0f);
  w.b = glm::vec4(B, 0.0f);
  const glm::vec3 axis = glm::normalize(B - A);
  const auto about_axis = [&](const glm::vec3& p) {
    const glm::vec3 d = p - A;
    return d - axis * glm::dot(d, axis);
  };
  const glm::vec3 to_centre = about_axis(glm::vec3(0.0f));
  const float radius = std::max(frame.half_width, frame.half_height);
  if (glm::length(to_centre) > 1e-4f * radius) {
    float lo = 0.0f, hi = 0.0f;
    glm::vec3 lo_corner(0.0f), hi_corner(0.0f);
    for (int c = 0; c < 4; ++c) {
      const glm::vec3 corner((c & 1) ? frame.half_width : -frame.half_width,
                             (c & 2) ? frame.half_height : -frame.half_height, 0.0f);
      const glm::vec3 w_c = about_axis(corner);
      const float angle =
          std::atan2(glm::dot(glm::cross(to_centre, w_c), axis), glm::dot(to_centre, w_c));
      if (angle < lo) lo = angle, lo_corner = corner;
      if (angle > hi) hi = angle, hi_corner = corner;
    }
    // The edge's line passes beside the light only if the corners span less
    // than a half turn about it; otherwise no two planes bound the wedge.
    if (lo < 0.0f && hi > 0.0f && hi - lo < 3.1f) {
      const glm::vec3 wa = frame.to_world(A), wb = frame.to_world(B);
      const glm::vec3 wlo = frame.to_world(lo_corner), whi = frame.to_world(hi_corner);
      glm::vec4 centre = plane_through(wa, wb, frame.center);
      if (glm::dot(centre, glm::vec4(wlo, 1.0f)) < 0.0f) centre = -centre;  // lo's side positive
      glm::vec4 first = plane_through(wa, wb, wlo), second = plane_through(wa, wb, whi);
      // The light on each bound's negative side: wedge points are positive.
      if (glm::dot(first, glm::vec4(frame.center, 1.0f)) > 0.0f) first = -first;
      if (glm::dot(second, glm::vec4(frame.center, 1.0f)) > 0.0f) second = -second;
      w.centre_plane = centre;
      w.first_bound = first;
      w.second_bound = second;
    }
  }
  out.wedges.push_back(w);
  return true;
}

IndexRange append_silhouette_wedges(const LightFrame& frame,
                                    const shadow_volume::Silhouette& silhouette,
                                    const WedgeRange& range, float tag, WedgeBatch& out) {
  IndexRange r;
  r.first = uint32_t(out.indices.size());
  for (const auto& loop : silhouette.loops)
    for (size_t i = 0; i < loop.size(); ++i)
      if (append_wedge(frame, loop[i].smooth, loop[(i + 1) % loop.size()].smooth, range, out))
        out.wedges.back().a.w = tag;
  r.count = uint32_t(out.indices.size()) - r.first;
  return r;
}

}  // namespace sb::techniques::penumbra_wedge
