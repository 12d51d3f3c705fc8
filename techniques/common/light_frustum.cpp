#include "common/light_frustum.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"

namespace sb::shadow {

LightFrustum fit_light_frustum(const Scene& scene, const glm::vec3& eye) {
  const Bounds casters = scene.caster_bounds();
  const Bounds all = scene.bounds();
  LightFrustum f;
  f.eye = eye;
  if (casters.empty()) {  // nothing casts: any frustum will do, every point is lit
    f.view_projection = glm::mat4(1.0f);
    return f;
  }
  const glm::vec3 c = casters.center();
  const float r = casters.radius() * 1.01f;
  const float d = glm::length(c - eye);
  if (d <= r) throw JobError("the light lies inside the casters' bounding sphere");
  const glm::vec3 dir = (c - eye) / d;
  const glm::vec3 up = std::fabs(dir.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  f.view = glm::lookAt(eye, c, up);
  const float half_angle = std::asin(std::min(r / d, 0.999f));
  f.near_plane = std::max(d - r, 1e-3f * d);
  // The far plane reaches the farthest receiver so that receiver depths stay
  // inside [0, 1]; lookups clamp anyway.
  float far_plane = d + r;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? all.hi.x : all.lo.x, (i & 2) ? all.hi.y : all.lo.y,
                           (i & 4) ? all.hi.z : all.lo.z);
    far_plane = std::max(far_plane, glm::length(corner - eye));
  }
  f.far_plane = far_plane * 1.01f;
  f.tan_half_fov = std::tan(half_angle);
  f.projection = glm::perspective(2.0f * half_angle, 1.0f, f.near_plane, f.far_plane);
  f.view_projection = f.projection * f.view;
  return f;
}

}  // namespace sb::shadow
