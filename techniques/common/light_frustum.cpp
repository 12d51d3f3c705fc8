#include "common/light_frustum.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <string>

#include "core/error.h"

namespace sb::techniques {

using core::Bounds;
using core::JobError;
using core::Mesh;
using core::Scene;

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

LightFrustum fit_light_frustum(const Scene& scene, const glm::vec3& eye, bool widen_for_light) {
  LightFrustum f;
  f.eye = eye;
  // The image plane is parallel to the light's rectangle (looking along its
  // axis), so one texel covers the same solid angle of every map technique
  // and PCSS's similar triangles hold across the whole map.
  const glm::vec3 axis = scene.light.direction();
  const glm::vec3 up = std::fabs(axis.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  f.view = glm::lookAt(eye, eye + axis, up);

  // The casters' extent seen from the eye, from every vertex a caster
  // triangle references: x/z and y/z in light view space, and the nearest
  // depth. Each vertex's extent grows by how far the rest of the light's
  // rectangle moves it (|L|/z for a light point L off the eye): receivers in
  // the outer penumbra must be inside the map, or a filtering technique would
  // call them lit by construction, not by its filter.
  const glm::mat3 rotate(f.view);
  const glm::vec3 hu = rotate * scene.light.half_u, hv = rotate * scene.light.half_v;
  const glm::vec3 centre_offset = rotate * (scene.light.center - eye);
  const glm::vec2 reach =
      widen_for_light ? glm::vec2(std::fabs(hu.x) + std::fabs(hv.x) + std::fabs(centre_offset.x),
                                  std::fabs(hu.y) + std::fabs(hv.y) + std::fabs(centre_offset.y))
                      : glm::vec2(0.0f);
  // The casters' size, not the scene's: a far-reaching ground would make a
  // caster just under the light look as if it reached the light's plane.
  const float scale = std::max(scene.caster_bounds().radius(), 1e-6f);
  float near_depth = std::numeric_limits<float>::max();
  glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const Mesh& m : scene.meshes) {
    if (!m.casts_shadow) continue;
    for (const uint32_t i : m.indices) {
      const glm::vec3 v(f.view * glm::vec4(m.positions[i], 1.0f));
      const float depth = -v.z;
      if (!(depth > 1e-4f * scale))
        throw JobError("caster mesh '" + m.name +
                       "' reaches the light's plane or behind it (a vertex at depth " +
                       std::to_string(depth) +
                       " along the light's axis): one perspective shadow map cannot cover it");
      near_depth = std::min(near_depth, depth);
      const glm::vec2 t(v.x / depth, v.y / depth);
      lo = glm::min(lo, t - reach / depth);
      hi = glm::max(hi, t + reach / depth);
    }
  }
  if (near_depth == std::numeric_limits<float>::max()) {  // nothing casts: every point is lit
    f.view_projection = glm::mat4(1.0f);
    return f;
  }
  // A square map (square texels), off-axis: centred on the casters' extent.
  const glm::vec2 centre = 0.5f * (lo + hi);
  const float half = 0.5f * std::max(hi.x - lo.x, hi.y - lo.y) * 1.01f + 1e-6f;
  constexpr float kWidest = 20.0f;  // tan of a half-angle of 87°
  if (!(half <= kWidest))
    throw JobError("the casters span more than 174 degrees seen from the light (tangent extent " +
                   std::to_string(2.0f * half) + "): one perspective shadow map cannot cover them");
  f.tan_half_fov = half;
  f.near_plane = near_depth * 0.99f;
  // The far plane reaches the farthest receiver inside the map's frustum, so
  // that every receiver the map covers has a depth in [0, 1] and the depth
  // range is no larger than it must be (filtered maps work on depth in that
  // range: a huge ground plane must not squeeze the casters into 1% of it).
  // The shear makes the off-axis frustum the symmetric cone the search needs.
  glm::mat4 shear(1.0f);
  shear[2][0] = centre.x;  // x' = x + cx·z: |x'| <= half·(−z) is the frustum
  shear[2][1] = centre.y;
  const float farthest = farthest_depth_in_cone(scene.bounds(), shear * f.view, half);
  f.far_plane = std::max(farthest, near_depth * 1.01f) * 1.01f;
  f.projection = glm::frustum((centre.x - half) * f.near_plane, (centre.x + half) * f.near_plane,
                              (centre.y - half) * f.near_plane, (centre.y + half) * f.near_plane,
                              f.near_plane, f.far_plane);
  f.view_projection = f.projection * f.view;
  return f;
}

glm::mat4 light_rotation(const glm::vec3& direction) {
  const glm::vec3 d = glm::normalize(direction);
  const glm::vec3 up = std::abs(d.y) > 0.99f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0, 1, 0);
  return glm::lookAt(glm::vec3(0.0f), d, up);
}

LightFrustum fit_sun_frustum(const Scene& scene) {
  LightFrustum f;
  f.orthographic = true;
  const glm::vec3 axis = scene.light.direction();
  const glm::mat4 rotation = light_rotation(axis);
  // Depth along the light in the rotation's frame: it looks down its -z.
  const auto depth = [&](const glm::vec3& p) { return -(rotation * glm::vec4(p, 1.0f)).z; };
  // The casters' extent across the light and their nearest depth.
  float caster_near = std::numeric_limits<float>::max();
  glm::vec2 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const Mesh& m : scene.meshes) {
    if (!m.casts_shadow) continue;
    for (const uint32_t i : m.indices) {
      const glm::vec3 v(rotation * glm::vec4(m.positions[i], 1.0f));
      caster_near = std::min(caster_near, -v.z);
      lo = glm::min(lo, glm::vec2(v));
      hi = glm::max(hi, glm::vec2(v));
    }
  }
  if (caster_near == std::numeric_limits<float>::max()) {  // nothing casts: every point is lit
    f.view_projection = glm::mat4(1.0f);
    return f;
  }
  // Every caster and receiver: the scene's box along the light.
  const Bounds box = scene.bounds();
  float lo_depth = std::numeric_limits<float>::max(), hi_depth = -lo_depth;
  for (int i = 0; i < 8; ++i) {
    const float d = depth({(i & 1) ? box.hi.x : box.lo.x, (i & 2) ? box.hi.y : box.lo.y,
                           (i & 4) ? box.hi.z : box.lo.z});
    lo_depth = std::min(lo_depth, d);
    hi_depth = std::max(hi_depth, d);
  }
  // The sun's disk moves a caster's shadow by tan(α/2) per unit depth behind
  // it: receivers in the outer penumbra must be inside the map, or a
  // filtering technique would call them lit by construction.
  const float reach =
      std::max(hi_depth - caster_near, 0.0f) * std::tan(0.5f * scene.light.angular_diameter);
  lo -= glm::vec2(reach);
  hi += glm::vec2(reach);
  const glm::vec2 centre = 0.5f * (lo + hi);
  const float span = std::max(hi.x - lo.x, hi.y - lo.y);
  f.half_extent = 0.5f * span * 1.01f + 1e-6f * std::max(box.radius(), 1.0f);
  // The eye on the sun's side of the box, a tenth of its depth span (at
  // least one unit) before it, so that every depth is positive.
  const float margin = 0.01f * (hi_depth - lo_depth) + 1e-4f * std::max(box.radius(), 1.0f);
  const float back = 0.1f * (hi_depth - lo_depth) + std::max(box.radius(), 1.0f) * 1e-2f;
  const glm::vec3 origin(glm::inverse(rotation) * glm::vec4(centre, 0.0f, 0.0f));
  f.eye = origin + (lo_depth - margin - back) * axis;
  f.view = glm::lookAt(f.eye, f.eye + axis,
                       glm::abs(axis.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0));
  // Depths from the eye: the rotation's, shifted.
  const float shift = depth(f.eye);
  f.near_plane = lo_depth - margin - shift;
  f.far_plane = hi_depth + margin - shift;
  f.projection = glm::ortho(-f.half_extent, f.half_extent, -f.half_extent, f.half_extent,
                            f.near_plane, f.far_plane);
  f.view_projection = f.projection * f.view;
  return f;
}

LightFrustum fit_single_map_frustum(const Scene& scene) {
  return scene.light.is_sun() ? fit_sun_frustum(scene)
                              : fit_light_frustum(scene, scene.light.center);
}

}  // namespace sb::techniques
