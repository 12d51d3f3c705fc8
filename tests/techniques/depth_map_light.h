#pragma once
// The light of the depth-map reconstruction tests (depth_map_cliffs,
// linear_light_skins): at the origin looking down -z, its 16² map covering
// x, y in [-z, z] at distance z.
#include <glm/gtc/matrix_transform.hpp>

#include "common/light_frustum.h"

namespace sb::techniques::test {

constexpr int kSize = 16;
constexpr float kNear = 1.0f, kFar = 10.0f;

inline LightFrustum light() {
  LightFrustum f;
  f.eye = glm::vec3(0.0f);
  f.view = glm::lookAt(f.eye, glm::vec3(0, 0, -1), glm::vec3(0, 1, 0));
  f.projection = glm::frustum(-kNear, kNear, -kNear, kNear, kNear, kFar);
  f.view_projection = f.projection * f.view;
  f.near_plane = kNear;
  f.far_plane = kFar;
  return f;
}

// The window depth of distance z along the light's axis.
inline float window(float z) {
  const glm::vec4 c = light().projection * glm::vec4(0.0f, 0.0f, -z, 1.0f);
  return 0.5f * (c.z / c.w) + 0.5f;
}

}  // namespace sb::techniques::test
