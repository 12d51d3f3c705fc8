#pragma once
// A closed caster's parts (exact_visibility.h): the triangles connected
// through shared edges, each a closed surface, oriented by its own signed
// volume; and the test of whether a point lies inside one.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "core/scene.h"
#include "reference/caster_bvh.h"
#include "reference/clipping.h"

namespace sb::reference::detail {

// Fills the closed casters' (outward != 0) CasterTriangle::neighbour,
// matching edges by vertex positions within each mesh; an edge shared by
// other than two triangles has none.
void link_neighbours(std::vector<CasterTriangle>& triangles);

// Labels the closed casters' parts through their neighbours and orients
// each by its own signed volume (CasterTriangle::outward); a part the light
// touches winds differently around its points, and is left open (outward
// 0, no part).
void find_parts(std::vector<CasterTriangle>& triangles, const core::AreaLight& light);

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
  bool winds_around_start();

 private:
  struct Crossing {
    uint32_t part;
    double s;
    bool leaves;  // along the part's outward normal
  };
  // One per thread, kept: a query per pixel would otherwise allocate.
  static std::vector<Crossing>& scratch();

  glm::dvec3 from_, to_centre_;
  std::vector<Crossing>& crossings_;
};

}  // namespace sb::reference::detail
