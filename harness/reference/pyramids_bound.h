#pragma once
// The pyramids from several points to a rectangular light (light_frame.h's
// pyramid()), bounded together: what a tile of neighbouring pixels culls
// the caster hierarchy with once, so that each of its pixels walks a short
// list of leaves instead of the whole hierarchy (exact_rectangle.cpp).
//
// The bound is a box and five planes. Each plane has the normal of a side
// (or of the light's plane) of the pyramid from the points' centroid, moved
// out until every point and every light corner lies inside it: each
// pyramid is the convex hull of its point and the corners, so it lies
// inside too, whatever the points. With the points close together (the
// usual tile) the planes are nearly the pyramids' own. Both the box and
// the planes are then moved out by a margin, 1e-9 of the largest
// coordinate involved, far beyond the rounding of any clip: a triangle
// that misses every pyramid by more than that leaves nothing after a
// pyramid's clip, and the segment from a point to the light's centre,
// inside its pyramid, cannot cross it.
#include <array>
#include <cstddef>
#include <glm/glm.hpp>

#include "reference/clipping.h"
#include "reference/light_frame.h"

namespace sb::reference::detail {

class PyramidsBound {
 public:
  // The pyramids from `count` points (count > 0) to the light of frame `f`;
  // `scale`: the largest |coordinate| of the boxes it will be asked about.
  PyramidsBound(const Frame& f, const glm::dvec3* points, size_t count, double scale);

  // False only when the box lies farther than the margin from every
  // pyramid.
  bool may_meet(const glm::dvec3& lo, const glm::dvec3& hi) const {
    return lo.x <= hi_.x && lo.y <= hi_.y && lo.z <= hi_.z && lo_.x <= hi.x && lo_.y <= hi.y &&
           lo_.z <= hi.z && box_meets(lo, hi, planes_);
  }

  // False only when the triangle abc lies farther than the margin from
  // every pyramid: wholly outside one of the planes.
  bool may_meet(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) const {
    for (const Plane& plane : planes_)
      if (plane.distance(a) < 0.0 && plane.distance(b) < 0.0 && plane.distance(c) < 0.0)
        return false;
    return true;
  }

 private:
  glm::dvec3 lo_, hi_;
  std::array<Plane, 5> planes_;
};

}  // namespace sb::reference::detail
