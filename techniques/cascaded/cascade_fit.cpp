#include "cascaded/cascade_fit.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace sb::techniques::cascaded {

std::vector<float> practical_splits(float near_plane, float far_plane, int cascades, float lambda) {
  std::vector<float> c(size_t(cascades) + 1);
  const double n = near_plane, f = far_plane, l = lambda;
  for (int i = 0; i <= cascades; ++i) {
    const double s = double(i) / double(cascades);
    c[size_t(i)] = float(l * n * std::pow(f / n, s) + (1.0 - l) * (n + (f - n) * s));
  }
  // Exact ends: the first cascade starts at the near plane, the last ends at the far one.
  c.front() = near_plane;
  c.back() = far_plane;
  return c;
}

std::array<glm::vec3, 8> slice_corners(const CameraFrustum& camera, float d0, float d1) {
  const glm::mat4 to_world = glm::inverse(camera.view);
  std::array<glm::vec3, 8> out;
  const float sx[4] = {-1.0f, 1.0f, 1.0f, -1.0f}, sy[4] = {-1.0f, -1.0f, 1.0f, 1.0f};
  for (int k = 0; k < 2; ++k) {
    const float d = k == 0 ? d0 : d1;
    const float hy = d * camera.tan_half_fov_y, hx = hy * camera.aspect;
    for (int j = 0; j < 4; ++j)
      out[size_t(4 * k + j)] = glm::vec3(to_world * glm::vec4(sx[j] * hx, sy[j] * hy, -d, 1.0f));
  }
  return out;
}

Sphere slice_bounding_sphere(const CameraFrustum& camera, float d0, float d1) {
  // The corners at depth d lie k·d from the axis, k² = tan_y²·(1 + aspect²).
  // A centre at depth c is as far from the near corners as from the far ones
  // where (c − d0)² + k²d0² = (d1 − c)² + k²d1², i.e. c = (d0 + d1)(1 + k²)/2;
  // past d1 (wide fields of view) the far rectangle's circumcircle is the answer.
  const double t = camera.tan_half_fov_y;
  const double k2 = t * t * (1.0 + double(camera.aspect) * camera.aspect);
  const double c = std::min(0.5 * (double(d0) + d1) * (1.0 + k2), double(d1));
  const double r = std::sqrt((d1 - c) * (d1 - c) + k2 * double(d1) * d1);
  const glm::mat4 to_world = glm::inverse(camera.view);
  return {glm::vec3(to_world * glm::vec4(0.0f, 0.0f, float(-c), 1.0f)), float(r)};
}

std::array<glm::vec3, 8> box_corners(const glm::vec3& lo, const glm::vec3& hi) {
  std::array<glm::vec3, 8> out;
  for (int i = 0; i < 8; ++i)
    out[size_t(i)] = {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
  return out;
}

CascadeBox fit_cascade(const CameraFrustum& camera, float d0, float d1,
                       const glm::vec3& light_direction,
                       const std::array<glm::vec3, 8>& caster_corners, int size, FitMode mode) {
  CascadeBox b;
  b.view = light_rotation(light_direction);
  // Depth along the light: the frame looks down its -z.
  const auto depth = [&](const glm::vec3& p) { return -(b.view * glm::vec4(p, 1.0f)).z; };
  float slice_near = 0.0f, slice_far = 0.0f;
  if (mode == FitMode::Stable) {
    const Sphere s = slice_bounding_sphere(camera, d0, d1);
    const glm::vec3 c = glm::vec3(b.view * glm::vec4(s.center, 1.0f));
    b.texel = 2.0f * s.radius / float(size);
    // Whole texels in the light's frame: the map's grid stays put in the world.
    const glm::vec2 snapped = glm::floor(glm::vec2(c) / b.texel) * b.texel;
    b.lo = snapped - glm::vec2(s.radius);
    b.hi = snapped + glm::vec2(s.radius);
    slice_near = -c.z - s.radius;
    slice_far = -c.z + s.radius;
  } else {
    b.lo = glm::vec2(1e30f);
    b.hi = glm::vec2(-1e30f);
    slice_near = 1e30f;
    slice_far = -1e30f;
    for (const glm::vec3& p : slice_corners(camera, d0, d1)) {
      const glm::vec3 q = glm::vec3(b.view * glm::vec4(p, 1.0f));
      b.lo = glm::min(b.lo, glm::vec2(q));
      b.hi = glm::max(b.hi, glm::vec2(q));
      slice_near = std::min(slice_near, -q.z);
      slice_far = std::max(slice_far, -q.z);
    }
    b.texel = std::max(b.hi.x - b.lo.x, b.hi.y - b.lo.y) / float(size);
  }
  // Every caster that can shadow the slice lies between the slice and the
  // sun: the near side reaches the casters' nearest point along the light.
  float caster_near = slice_near;
  for (const glm::vec3& p : caster_corners) caster_near = std::min(caster_near, depth(p));
  const float margin = 1e-3f * std::max(slice_far - caster_near, 1e-3f);
  b.near_depth = caster_near - margin;
  b.far_depth = slice_far + margin;
  b.projection = glm::ortho(b.lo.x, b.hi.x, b.lo.y, b.hi.y, b.near_depth, b.far_depth);
  b.view_projection = b.projection * b.view;
  return b;
}

CascadeBox fit_light_bounds(const glm::vec3& lo, const glm::vec3& hi,
                            const glm::vec3& light_direction,
                            const std::array<glm::vec3, 8>& caster_corners, int size,
                            float pad_texels) {
  CascadeBox b;
  b.view = light_rotation(light_direction);
  const auto depth = [&](const glm::vec3& p) { return -(b.view * glm::vec4(p, 1.0f)).z; };
  // A partition of one sample (or one line of them) still gets a box.
  const float floor_extent = 1e-4f * (1.0f + std::max(glm::length(glm::vec2(lo)), 1.0f));
  const glm::vec2 samples = glm::max(glm::vec2(hi) - glm::vec2(lo), glm::vec2(floor_extent));
  // The padded extent E holds the samples' e and pad texels of E / size on each side.
  const float keep = std::max(float(size) - 2.0f * pad_texels, 1.0f);
  const glm::vec2 extent = samples * (float(size) / keep);
  const glm::vec2 pad = extent * (pad_texels / float(size));
  const glm::vec2 centre = 0.5f * (glm::vec2(lo) + glm::vec2(hi));
  b.lo = centre - 0.5f * samples - pad;
  b.hi = centre + 0.5f * samples + pad;
  b.texel = std::max(extent.x, extent.y) / float(size);
  float caster_near = lo.z;
  for (const glm::vec3& p : caster_corners) caster_near = std::min(caster_near, depth(p));
  // The normal offset may move a sample's lookup point a few texels further.
  const float far = hi.z + pad_texels * b.texel;
  const float margin = 1e-3f * std::max(far - caster_near, 1e-3f);
  b.near_depth = caster_near - margin;
  b.far_depth = far + margin;
  b.projection = glm::ortho(b.lo.x, b.hi.x, b.lo.y, b.hi.y, b.near_depth, b.far_depth);
  b.view_projection = b.projection * b.view;
  return b;
}

CascadePlan plan_cascades(const CameraFrustum& camera, float near_plane, float far_plane,
                          int cascades, float lambda, float blend_band,
                          const glm::vec3& light_direction,
                          const std::array<glm::vec3, 8>& caster_corners, int size, FitMode mode) {
  CascadePlan plan;
  plan.splits = practical_splits(near_plane, far_plane, cascades, lambda);
  for (int i = 0; i < cascades; ++i) {
    const float d0 = plan.splits[size_t(i)], d1 = plan.splits[size_t(i) + 1];
    plan.bands.push_back(i + 1 < cascades ? blend_band * (d1 - d0) : 0.0f);
    const float start = i > 0 ? std::max(d0 - plan.bands[size_t(i) - 1], near_plane) : d0;
    plan.boxes.push_back(
        fit_cascade(camera, start, d1, light_direction, caster_corners, size, mode));
  }
  return plan;
}

glm::vec3 box_coords(const CascadeBox& box, const glm::vec3& world) {
  const glm::vec4 c = box.view_projection * glm::vec4(world, 1.0f);
  return glm::vec3(c) / c.w * 0.5f + 0.5f;
}

}  // namespace sb::techniques::cascaded
