#pragma once
// The area light as the exact reference sees it (exact_visibility.h): its
// frame, the pyramid it spans from a point, and the box around it.
#include <array>
#include <glm/glm.hpp>

#include "core/scene.h"
#include "reference/clipping.h"

namespace sb::reference::detail {

// The light's frame: centre, unit axes along half_u and half_v, the unit
// normal, and the half sizes.
struct Frame {
  glm::dvec3 centre, u, v, normal;
  double hw = 0.0, hh = 0.0;
  explicit Frame(const core::AreaLight& l)
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
std::array<Plane, 5> pyramid(const Frame& f, const glm::dvec3& p);

// The light (a rectangle or a segment) grown by a hair, 1e-6 of its size,
// on every side, as the six planes of a box facing in.
std::array<Plane, 6> light_box(const core::AreaLight& l);

}  // namespace sb::reference::detail
