#include "shadow_volume/near_plane_pyramid.h"

namespace sb::techniques::shadow_volume {

using core::Bounds;

namespace {
glm::vec4 plane_through(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3 n = glm::cross(b - a, c - a);
  return {n, -glm::dot(n, a)};
}
float side(const glm::vec4& plane, const glm::vec3& p) {
  return glm::dot(glm::vec3(plane), p) + plane.w;
}
}  // namespace

NearPlanePyramid::NearPlanePyramid(const glm::vec3& light, const glm::mat4& view_projection) {
  const glm::mat4 inverse = glm::inverse(view_projection);
  std::array<glm::vec3, 4> corner{};
  const std::array<glm::vec2, 4> ndc{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};
  for (size_t i = 0; i < 4; ++i) {
    const glm::vec4 p = inverse * glm::vec4(ndc[i], -1.0f, 1.0f);
    corner[i] = glm::vec3(p) / p.w;
  }
  const glm::vec3 inside = 0.2f * (light + corner[0] + corner[1] + corner[2] + corner[3]);
  planes_[4] = plane_through(corner[0], corner[1], corner[2]);
  for (size_t i = 0; i < 4; ++i) planes_[i] = plane_through(light, corner[i], corner[(i + 1) % 4]);
  // Through the light, facing away from the rectangle: the box test alone
  // would let a box larger than the apex straddle the side planes behind it.
  const glm::vec3 towards = 0.25f * (corner[0] + corner[1] + corner[2] + corner[3]) - light;
  planes_[5] = glm::vec4(-towards, glm::dot(towards, light));
  const float scale = glm::length(corner[2] - corner[0]) + glm::length(light - corner[0]);
  for (glm::vec4& plane : planes_) {
    const float s = side(plane, inside);
    // Flat: the light on (or too near) the rectangle's plane.
    if (glm::length(glm::vec3(plane)) <= 1e-12f * scale * scale || s == 0.0f) degenerate_ = true;
    if (s > 0.0f) plane = -plane;
  }
}

bool NearPlanePyramid::may_intersect(const Bounds& box) const {
  if (degenerate_ || box.empty()) return !box.empty();
  for (const glm::vec4& plane : planes_) {
    // The box corner farthest inside; if even it is outside, the box is.
    const glm::vec3 n(plane);
    const glm::vec3 p(n.x > 0 ? box.lo.x : box.hi.x, n.y > 0 ? box.lo.y : box.hi.y,
                      n.z > 0 ? box.lo.z : box.hi.z);
    if (side(plane, p) > 0.0f) return false;
  }
  return true;
}

}  // namespace sb::techniques::shadow_volume
