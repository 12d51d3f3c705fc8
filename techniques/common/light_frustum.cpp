#include "common/light_frustum.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"

namespace sb::shadow {
namespace {

// The largest distance along the light's axis of any point of `box` inside
// the square cone {|x|, |y| <= tan_half·(−z)} of `view`. That maximum of a
// linear function over a convex polytope is reached at one of its vertices:
// a box corner inside the cone, a cone edge leaving through a box face, or a
// box edge crossing a side plane of the cone.
float farthest_depth_in_cone(const Bounds& box, const glm::mat4& view, float tan_half) {
  const float slack = 1e-4f;
  const auto in_cone = [&](const glm::vec3& world) {
    const glm::vec3 v = glm::vec3(view * glm::vec4(world, 1.0f));
    const float limit = -v.z * tan_half * (1.0f + slack) + slack;
    return -v.z > 0.0f && std::fabs(v.x) <= limit && std::fabs(v.y) <= limit;
  };
  const auto in_box = [&](const glm::vec3& p) {
    const glm::vec3 pad = slack * (box.hi - box.lo) + glm::vec3(slack);
    return glm::all(glm::greaterThanEqual(p, box.lo - pad)) &&
           glm::all(glm::lessThanEqual(p, box.hi + pad));
  };
  const glm::mat4 to_world = glm::inverse(view);
  const glm::vec3 eye(to_world[3]);
  float farthest = 0.0f;
  const auto consider = [&](const glm::vec3& p) {
    farthest = std::max(farthest, -(view * glm::vec4(p, 1.0f)).z);
  };
  glm::vec3 corners[8];
  for (int i = 0; i < 8; ++i) {
    corners[i] = {(i & 1) ? box.hi.x : box.lo.x, (i & 2) ? box.hi.y : box.lo.y,
                  (i & 4) ? box.hi.z : box.lo.z};
    if (in_cone(corners[i])) consider(corners[i]);
  }
  // Cone edges against the box's six face planes.
  for (int e = 0; e < 4; ++e) {
    const glm::vec3 dir = glm::vec3(to_world * glm::vec4((e & 1) ? tan_half : -tan_half,
                                                         (e & 2) ? tan_half : -tan_half, -1, 0));
    for (int axis = 0; axis < 3; ++axis) {
      if (std::fabs(dir[axis]) < 1e-12f) continue;
      for (const float plane : {box.lo[axis], box.hi[axis]}) {
        const float t = (plane - eye[axis]) / dir[axis];
        if (t > 0.0f && in_box(eye + t * dir)) consider(eye + t * dir);
      }
    }
  }
  // Box edges against the cone's four side planes (through the eye).
  for (int side = 0; side < 4; ++side) {
    const float sx = (side == 0) ? 1.0f : (side == 1) ? -1.0f : 0.0f;
    const float sy = (side == 2) ? 1.0f : (side == 3) ? -1.0f : 0.0f;
    // In view space the plane is s·(x, y) = tan_half·(−z): n·v = 0 with
    // n = (sx, sy, tan_half).
    const glm::vec3 n(sx, sy, tan_half);
    for (int i = 0; i < 8; ++i)
      for (int bit = 1; bit < 8; bit <<= 1) {
        if (i & bit) continue;
        const glm::vec3 a = glm::vec3(view * glm::vec4(corners[i], 1.0f));
        const glm::vec3 b = glm::vec3(view * glm::vec4(corners[i | bit], 1.0f));
        const float da = glm::dot(n, a), db = glm::dot(n, b);
        if ((da > 0.0f) == (db > 0.0f) || da == db) continue;
        const glm::vec3 p = glm::mix(corners[i], corners[i | bit], da / (da - db));
        if (in_cone(p)) consider(p);
      }
  }
  return farthest;
}

}  // namespace

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
  f.tan_half_fov = std::tan(half_angle);
  // The far plane reaches the farthest receiver inside the map's cone, so
  // that every receiver the map covers has a depth in [0, 1] and the depth
  // range is no larger than it must be (filtered maps work on depth in that
  // range: a huge ground plane must not squeeze the casters into 1% of it).
  f.far_plane = std::max(d + r, farthest_depth_in_cone(all, f.view, f.tan_half_fov)) * 1.01f;
  f.projection = glm::perspective(2.0f * half_angle, 1.0f, f.near_plane, f.far_plane);
  f.view_projection = f.projection * f.view;
  return f;
}

}  // namespace sb::shadow
