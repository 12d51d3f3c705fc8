#include "reference/light_frame.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace sb::reference::detail {

using core::AreaLight;

namespace {

// A unit vector perpendicular to the unit vector d.
glm::dvec3 any_perpendicular(const glm::dvec3& d) {
  const glm::dvec3 axis = std::fabs(d.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(d, axis));
}

}  // namespace

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

}  // namespace sb::reference::detail
