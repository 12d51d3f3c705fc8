#include "reference/ray_offset.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

namespace sb::reference::detail {
namespace {

double largest_coordinate(const glm::dvec3& v) {
  return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
}

// What the point query gathers: the largest |coordinate| M of the caster
// triangles that p lies on, up to their own rounding.
struct Gather {
  const Scene* scene;
  const std::vector<size_t>* mesh_of_geometry;
  const std::vector<AnalyticShape::Kind>* shape_of_geometry;
  glm::dvec3 p;
  double largest = 0.0;
};

// Called for every caster triangle whose bounds meet the query sphere.
// Returns false: the query radius stays as it is.
bool on_triangle(RTCPointQueryFunctionArguments* args) {
  auto* g = static_cast<Gather*>(args->userPtr);
  // An analytic shape (whether or not Embree's point query visits it) adds
  // nothing: a ray never meets its own mesh's shape (the sphere filter in
  // embree_scene.cpp), and a point lies on another mesh's shape only where
  // two casters touch.
  if ((*g->shape_of_geometry)[args->geomID] != AnalyticShape::Kind::None) return false;
  const Mesh& m = g->scene->meshes[(*g->mesh_of_geometry)[args->geomID]];
  const size_t first = size_t(args->primID) * 3;
  const glm::dvec3 a(m.positions[m.indices[first]]), b(m.positions[m.indices[first + 1]]),
      c(m.positions[m.indices[first + 2]]);
  const double size =
      std::max({largest_coordinate(a), largest_coordinate(b), largest_coordinate(c)});
  if (size <= g->largest) return false;  // cannot raise M
  const double reach = double(kOffsetRelative) * size;
  const glm::dvec3 lo = glm::min(a, glm::min(b, c)) - reach,
                   hi = glm::max(a, glm::max(b, c)) + reach;
  if (glm::any(glm::lessThan(g->p, lo)) || glm::any(glm::greaterThan(g->p, hi))) return false;
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double area2 = glm::length(n);
  if (!(area2 > 0.0)) return false;
  if (std::fabs(glm::dot(g->p - a, n)) <= reach * area2) g->largest = size;
  return false;
}

}  // namespace

float RayOffset::at(const glm::vec3& p) const {
  const float own = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  if (casters_.empty()) return kOffsetRelative * own;
  Gather g{&scene_, &casters_.mesh_of_geometry, &casters_.shape_of_geometry, glm::dvec3(p)};
  RTCPointQuery query;
  query.x = p.x;
  query.y = p.y;
  query.z = p.z;
  // p lies on its triangle up to the rounding of its own coordinates.
  query.radius = kOffsetRelative * own;
  query.time = 0.0f;
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(casters_.get(), &query, &context, on_triangle, &g);
  return kOffsetRelative * std::max(own, float(g.largest));
}

}  // namespace sb::reference::detail
