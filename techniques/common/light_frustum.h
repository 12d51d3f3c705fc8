#pragma once
// A perspective light view from one point of the area light, fitted to the
// casters' bounding sphere: receivers outside it cannot be shadowed from that
// point, so they are lit by construction (the map's border reads "far").
#include <glm/glm.hpp>

#include "core/scene.h"

namespace sb::shadow {

struct LightFrustum {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
  glm::mat4 view_projection{1.0f};
  glm::vec3 eye{0.0f};
  float near_plane = 0.1f;
  float far_plane = 100.0f;
  float tan_half_fov = 1.0f;
  // World-space size of one texel of a size×size map, per unit distance from eye.
  float texel_per_distance(int size) const { return 2.0f * tan_half_fov / float(size); }
};

// Throws sb::JobError when `eye` lies inside the casters' bounding sphere
// (a single perspective map cannot cover it).
LightFrustum fit_light_frustum(const Scene& scene, const glm::vec3& eye);

}  // namespace sb::shadow
