#include "reference/closed_parts.h"

#include <algorithm>
#include <array>
#include <tuple>
#include <utility>

#include "reference/light_frame.h"

namespace sb::reference::detail {

using core::AreaLight;

void link_neighbours(std::vector<CasterTriangle>& triangles) {
  struct Edge {
    uint32_t mesh;
    std::array<double, 6> ends;  // the lesser end first
    uint32_t triangle;
    int k;
    bool operator<(const Edge& o) const { return std::tie(mesh, ends) < std::tie(o.mesh, o.ends); }
    bool same(const Edge& o) const { return mesh == o.mesh && ends == o.ends; }
  };
  std::vector<Edge> edges;
  for (uint32_t i = 0; i < triangles.size(); ++i) {
    const CasterTriangle& t = triangles[i];
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
      triangles[edges[e].triangle].neighbour[size_t(edges[e].k)] = edges[e + 1].triangle;
      triangles[edges[e + 1].triangle].neighbour[size_t(edges[e + 1].k)] = edges[e].triangle;
    }
    e = end;
  }
}

void find_parts(std::vector<CasterTriangle>& triangles, const AreaLight& light_shape) {
  const std::array<Plane, 6> light = light_box(light_shape);
  std::vector<uint32_t> part_triangles;
  uint32_t parts = 0;
  for (uint32_t seed = 0; seed < triangles.size(); ++seed) {
    if (triangles[seed].outward == 0 || triangles[seed].part != kNoPart) continue;
    // Every triangle reached through shared edges (each closed caster's
    // edge has exactly two).
    const uint32_t part = parts++;
    triangles[seed].part = part;
    part_triangles.assign(1, seed);
    // Six times the signed volume, about a corner of the part's own (its
    // rounding scales with the part's size, not with its distance).
    const glm::dvec3 origin = triangles[seed].a;
    double volume = 0.0;
    bool touches_light = false;
    for (size_t q = 0; q < part_triangles.size(); ++q) {
      const CasterTriangle& t = triangles[part_triangles[q]];
      volume += glm::dot(t.a - origin, glm::cross(t.b - origin, t.c - origin));
      // The sun is at infinity: no part touches it.
      touches_light =
          touches_light || (!light_shape.is_sun() && triangle_meets(t.a, t.b, t.c, light));
      for (const uint32_t across : t.neighbour)
        if (across != kNoNeighbour && triangles[across].part == kNoPart) {
          triangles[across].part = part;
          part_triangles.push_back(across);
        }
    }
    // A part the light touches winds differently around its points: it
    // keeps every triangle, as an open caster does.
    const int outward = touches_light ? 0 : volume < 0.0 ? -1 : 1;
    for (const uint32_t i : part_triangles) {
      triangles[i].outward = outward;
      if (touches_light) triangles[i].part = kNoPart;
    }
  }
}

bool PartCrossings::winds_around_start() {
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

std::vector<PartCrossings::Crossing>& PartCrossings::scratch() {
  thread_local std::vector<Crossing> crossings;
  return crossings;
}

}  // namespace sb::reference::detail
