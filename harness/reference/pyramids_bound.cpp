#include "reference/pyramids_bound.h"

#include <algorithm>
#include <cmath>

namespace sb::reference::detail {

PyramidsBound::PyramidsBound(const Frame& f, const glm::dvec3* points, size_t count, double scale) {
  const auto corners = f.corners();
  lo_ = hi_ = corners[0];
  glm::dvec3 centroid(0.0);
  double largest = scale;
  const auto extend = [&](const glm::dvec3& x) {
    lo_ = glm::min(lo_, x);
    hi_ = glm::max(hi_, x);
    largest = std::max({largest, std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)});
  };
  for (const glm::dvec3& c : corners) extend(c);
  for (size_t i = 0; i < count; ++i) {
    extend(points[i]);
    centroid += points[i];
  }
  centroid /= double(count);
  const double margin = 1e-9 * largest;
  lo_ -= margin;
  hi_ += margin;
  planes_ = pyramid(f, centroid);
  for (Plane& plane : planes_) {
    const double length = glm::length(plane.normal);
    if (!(length > 0.0) || !std::isfinite(length)) {
      // No direction: a plane that keeps everything.
      plane = {glm::dvec3(0.0), glm::dvec3(0.0)};
      continue;
    }
    const glm::dvec3 unit = plane.normal / length;
    double nearest = glm::dot(unit, corners[0]);
    for (const glm::dvec3& c : corners) nearest = std::min(nearest, glm::dot(unit, c));
    for (size_t i = 0; i < count; ++i) nearest = std::min(nearest, glm::dot(unit, points[i]));
    plane = {unit, unit * (nearest - margin)};
  }
}

}  // namespace sb::reference::detail
