#pragma once
// The area light's own orthonormal frame, shared by the families that work
// in it (penumbra wedges, occlusion textures): u along half_u, n towards the
// light's target (the lit side), v = n × u, origin at the light's centre, so
// the light is the rectangle |x| <= half_width, |y| <= half_height of z = 0
// and the scene lies at z > 0.
//
// What the kit guarantees here (shadowbench::shadow_kit, installed): header
// only, plain CPU code (no GL), world units; each call O(1).
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "core/scene.h"

namespace sb::techniques {

// The area light's frame (u, v, n, its centre) and its half extents;
// to_light() and to_world() convert points between it and the world.
// units: world units.
// cost: O(1) per call; no GL.
struct LightFrame {
  glm::vec3 center{0.0f};
  glm::vec3 u{1.0f, 0.0f, 0.0f}, v{0.0f, 1.0f, 0.0f}, n{0.0f, 0.0f, 1.0f};
  float half_width = 0.5f, half_height = 0.5f;

  LightFrame() = default;
  explicit LightFrame(const core::AreaLight& light)
      : center(light.center),
        half_width(glm::length(light.half_u)),
        half_height(glm::length(light.half_v)) {
    // A light of no area (a config's light_size 0) keeps a frame about its
    // direction, so that nothing here divides by zero; it has no penumbra.
    const glm::vec3 normal = glm::cross(light.half_u, light.half_v);
    n = glm::length(normal) > 0.0f ? glm::normalize(normal)
                                   : glm::normalize(light.target - light.center);
    if (glm::dot(n, light.target - light.center) < 0.0f) n = -n;
    if (half_width > 0.0f) {
      u = light.half_u / half_width;
    } else if (half_height > 0.0f) {
      // A segment along half_v (light.size [0, h]): v must run along it.
      v = light.half_v / half_height;
      u = glm::normalize(glm::cross(v, n));
      return;
    } else {
      const glm::vec3 across = std::fabs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
      u = glm::normalize(glm::cross(across, n));
    }
    v = glm::cross(n, u);
  }
  bool has_area() const { return half_width > 0.0f && half_height > 0.0f; }
  glm::vec3 to_light(const glm::vec3& world) const {
    const glm::vec3 d = world - center;
    return {glm::dot(d, u), glm::dot(d, v), glm::dot(d, n)};
  }
  glm::vec3 to_world(const glm::vec3& local) const {
    return center + local.x * u + local.y * v + local.z * n;
  }
  // Light-frame z of the farthest corner of `box`.
  float farthest(const core::Bounds& box) const {
    float z = -1e30f;
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 corner((i & 1) ? box.hi.x : box.lo.x, (i & 2) ? box.hi.y : box.lo.y,
                             (i & 4) ? box.hi.z : box.lo.z);
      z = std::max(z, to_light(corner).z);
    }
    return z;
  }
};

}  // namespace sb::techniques
