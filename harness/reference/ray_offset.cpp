#include "reference/ray_offset.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

namespace sb::reference::detail {

using core::AnalyticShape;
using core::Mesh;
using core::Scene;

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
  double radius;
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
  g->largest =
      std::max(g->largest, lies_on_scale(g->p, g->radius, glm::dvec3(m.positions[m.indices[first]]),
                                         glm::dvec3(m.positions[m.indices[first + 1]]),
                                         glm::dvec3(m.positions[m.indices[first + 2]])));
  return false;
}

}  // namespace

double offset_radius(const glm::dvec3& p) {
  return double(kOffsetRelative) * largest_coordinate(p);
}

double lies_on_scale(const glm::dvec3& p, double radius, const glm::dvec3& a, const glm::dvec3& b,
                     const glm::dvec3& c) {
  // Within the radius of the triangle's bounds: this, not whichever leaf of
  // Embree's hierarchy visited it, decides (the exact reference has none).
  const glm::dvec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
  const glm::dvec3 outside = glm::max(lo - p, glm::max(p - hi, glm::dvec3(0.0)));
  if (!(glm::dot(outside, outside) <= radius * radius)) return 0.0;
  const double size =
      std::max({largest_coordinate(a), largest_coordinate(b), largest_coordinate(c)});
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double area2 = glm::length(n);
  if (!(area2 > 0.0)) return 0.0;
  return std::fabs(glm::dot(p - a, n)) <= double(kOffsetRelative) * size * area2 ? size : 0.0;
}

double offset_from(const glm::dvec3& p, double largest) {
  return double(kOffsetRelative) * std::max(largest_coordinate(p), largest);
}

float RayOffset::at(const glm::vec3& p) const {
  const glm::dvec3 point(p);
  if (casters_.empty()) return float(offset_from(point, 0.0));
  Gather g{&scene_, &casters_.mesh_of_geometry, &casters_.shape_of_geometry, point,
           offset_radius(point)};
  RTCPointQuery query;
  query.x = p.x;
  query.y = p.y;
  query.z = p.z;
  // p lies on its triangle up to the rounding of its own coordinates.
  query.radius = float(g.radius);
  query.time = 0.0f;
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(casters_.get(), &query, &context, on_triangle, &g);
  return float(offset_from(point, g.largest));
}

}  // namespace sb::reference::detail
