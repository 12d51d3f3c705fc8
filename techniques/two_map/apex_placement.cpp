#include "two_map/apex_placement.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace sb::techniques::two_map {

using core::Bounds;
using core::JobError;

TwoApexes place_apexes(const LightFrame& light, const Bounds& casters) {
  glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  float depth = std::numeric_limits<float>::max();
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? casters.hi.x : casters.lo.x,
                           (i & 2) ? casters.hi.y : casters.lo.y,
                           (i & 4) ? casters.hi.z : casters.lo.z);
    const glm::vec3 local = light.to_light(corner);
    lo = glm::min(lo, glm::vec2(local));
    hi = glm::max(hi, glm::vec2(local));
    depth = std::min(depth, local.z);
  }
  if (!(depth > 0.0f))
    throw JobError("the casters reach the light's plane (nearest depth " + std::to_string(depth) +
                   "): no apex in front of the light bounds their penumbra");
  TwoApexes a;
  a.caster_depth = depth;
  const glm::vec2 centre = 0.5f * (lo + hi), c = 0.5f * (hi - lo);
  const glm::vec2 l(light.half_width, light.half_height);
  // On the line from the extent's centre (at depth D) through the light's centre.
  const auto on_axis_line = [&](float z) {
    return light.to_world(glm::vec3(centre * (z / depth), z));
  };
  float zp = 0.0f;
  for (int k = 0; k < 2; ++k)
    zp = std::max(zp, c[k] + l[k] > 0.0f ? depth * l[k] / (c[k] + l[k]) : 0.0f);
  a.penumbra_depth = zp;
  a.penumbra_apex = on_axis_line(zp);
  if (c.x > l.x && c.y > l.y) {
    float zu = 0.0f;
    for (int k = 0; k < 2; ++k) zu = std::min(zu, -depth * l[k] / (c[k] - l[k]));
    a.has_umbra_apex = true;
    a.umbra_depth = std::max(zu, -kFarthestUmbraApex * depth);
    a.umbra_apex = on_axis_line(a.umbra_depth);
  }
  return a;
}

}  // namespace sb::techniques::two_map
