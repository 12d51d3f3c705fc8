#include "shadow_map/perspective_warp.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <string>
#include <vector>

#include "common/convex_body.h"
#include "core/error.h"

namespace sb::techniques::shadow_map {

using core::Bounds;
using core::JobError;
using core::Mesh;
using core::Scene;

namespace {

constexpr float kInf = std::numeric_limits<float>::max();

struct Range {
  float lo = kInf, hi = -kInf;
  void add(float v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool empty() const { return !(hi >= lo); }
  float size() const { return hi - lo; }
};

// The affine map of the box x×y×z onto [-1, 1]^3 (a degenerate side keeps a
// unit extent, so nothing divides by zero).
glm::mat4 box_to_clip(Range x, Range y, Range z) {
  glm::mat4 m(1.0f);
  const Range* axes[3] = {&x, &y, &z};
  for (int i = 0; i < 3; ++i) {
    const float size = std::max(axes[i]->size(), 1e-12f);
    m[i][i] = 2.0f / size;
    m[3][i] = -1.0f - 2.0f * axes[i]->lo / size;
  }
  return m;
}

glm::vec3 euclid(const glm::vec4& h) { return glm::vec3(h) / h.w; }

glm::vec3 up_for(const glm::vec3& axis) {
  return std::fabs(axis.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
}

bool overlaps(const Bounds& a, const Bounds& b) {
  return glm::all(glm::lessThanEqual(a.lo, b.hi)) && glm::all(glm::lessThanEqual(b.lo, a.hi));
}

// The vertices of the casters whose box meets `reach`: the only ones that
// can shadow a point of `reach` from a light inside it.
std::vector<glm::vec3> casters_within(const Scene& scene, const std::vector<Bounds>& boxes,
                                      const Bounds& reach) {
  std::vector<glm::vec3> points;
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const Mesh& m = scene.meshes[i];
    if (m.casts_shadow && overlaps(boxes[i], reach))
      points.insert(points.end(), m.positions.begin(), m.positions.end());
  }
  return points;
}

// A camera projection with its near and far planes replaced (the x and y
// rows, off-axis terms included, are kept).
glm::mat4 with_depth_range(glm::mat4 p, float near, float far) {
  p[2][2] = -(far + near) / (far - near);
  p[3][2] = -2.0f * far * near / (far - near);
  return p;
}

float camera_depth(const glm::mat4& view, const glm::vec3& p) {
  return -(view * glm::vec4(p, 1.0f)).z;
}

glm::vec3 camera_forward(const glm::mat4& view) {
  return -glm::normalize(glm::vec3(view[0][2], view[1][2], view[2][2]));
}

LightFrustum centre_frame(const Scene& scene) {
  LightFrustum f;
  f.eye = scene.light.center;
  const glm::vec3 axis = scene.light.direction();
  f.view = glm::lookAt(f.eye, f.eye + axis, up_for(axis));
  return f;
}

}  // namespace

LightFrustum fit_psm(const Scene& scene, const std::vector<Bounds>& boxes, const CameraView& camera,
                     WarpInfo* info) {
  WarpInfo local;
  WarpInfo& out = info != nullptr ? *info : local;
  const glm::vec3 light = scene.light.center;
  const std::vector<glm::vec3> body =
      visible_body(boxes, frustum_planes(camera.projection * camera.view));
  if (body.empty()) return fit_light_frustum(scene, light, false);

  // The body's depth range seen from the camera: the virtual camera's near
  // plane sits at the nearest visible point, not at the camera's own near
  // plane, which would spend the map on empty space (the paper's "tight
  // near plane").
  Range depth;
  Bounds reach;
  reach.extend(light);
  for (const auto& p : body) {
    depth.add(camera_depth(camera.view, p));
    reach.extend(p);
  }
  const float z_near = std::max(depth.lo, 1e-6f * std::max(depth.hi, 1e-6f));
  const std::vector<glm::vec3> casters = casters_within(scene, boxes, reach);
  Range caster_depth;
  for (const auto& p : casters) caster_depth.add(camera_depth(camera.view, p));
  // The virtual camera moves back until every caster that can shadow the
  // body is in front of its near plane (post-perspective space keeps the
  // order of points only in front of the camera).
  const float shift = caster_depth.empty() ? 0.0f : std::max(0.0f, z_near - caster_depth.lo);
  out.virtual_shift = shift;
  const float z_far = std::max(depth.hi + shift, z_near * 1.001f);
  const glm::mat4 virtual_view =
      glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -shift)) * camera.view;
  const glm::mat4 to_pps = with_depth_range(camera.projection, z_near, z_far) * virtual_view;

  const glm::vec4 light_pps = to_pps * glm::vec4(light, 1.0f);
  out.light_behind_camera = light_pps.w < 0.0f;
  std::vector<glm::vec3> region, occluders;
  glm::vec3 centroid(0.0f);
  for (const auto& p : body) {
    region.push_back(euclid(to_pps * glm::vec4(p, 1.0f)));
    centroid += region.back();
  }
  centroid /= float(region.size());
  for (const auto& p : casters) occluders.push_back(euclid(to_pps * glm::vec4(p, 1.0f)));

  LightFrustum f = centre_frame(scene);
  const float light_scale = glm::length(glm::vec3(light_pps));
  glm::mat4 map(1.0f);
  if (std::fabs(light_pps.w) <= 1e-6f * light_scale) {
    // The light lies in the camera's plane: its image is at infinity, and
    // its rays are parallel there, travelling along -light_pps.xyz (the
    // direction in which a point moving away from the light moves).
    const glm::vec3 axis = -glm::normalize(glm::vec3(light_pps));
    const glm::mat4 look = glm::lookAt(centroid - axis, centroid, up_for(axis));
    Range x, y, z;
    for (const auto& p : region) {
      const glm::vec3 v(look * glm::vec4(p, 1.0f));
      x.add(v.x);
      y.add(v.y);
      z.add(-v.z);
    }
    for (const auto& p : occluders) z.add(-(look * glm::vec4(p, 1.0f)).z);
    map = box_to_clip(x, y, z) * glm::scale(glm::mat4(1.0f), glm::vec3(1, 1, -1)) * look;
  } else {
    // A perspective view from the light's image. Behind the camera's plane
    // (w < 0) that image lies past infinity: the scene is still in front of
    // it, but a point farther from the light in the world is nearer to it
    // here, so the map's depth is inverted.
    const glm::vec3 eye = glm::vec3(light_pps) / light_pps.w;
    const glm::vec3 axis = glm::normalize(centroid - eye);
    const glm::mat4 look = glm::lookAt(eye, centroid, up_for(axis));
    Range tx, ty, z;
    for (const auto& p : region) {
      const glm::vec3 v(look * glm::vec4(p, 1.0f));
      const float d = -v.z;
      if (!(d > 1e-6f * glm::length(v)))
        throw JobError(
            "psm: the light's image in the camera's post-perspective space lies inside or beside "
            "the visible scene (a light in the view, facing the camera): one map cannot cover "
            "it (the paper uses a cube map there)");
      tx.add(v.x / d);
      ty.add(v.y / d);
      z.add(d);
    }
    for (const auto& p : occluders) {
      const float d = -(look * glm::vec4(p, 1.0f)).z;
      if (d > 0.0f) z.add(d);
    }
    const float half = 0.5f * std::max(tx.size(), ty.size()) * 1.01f + 1e-6f;
    if (!(half <= 20.0f))
      throw JobError(
          "psm: the visible scene spans more than 174 degrees seen from the light's "
          "post-perspective image: one map cannot cover it");
    const float cx = 0.5f * (tx.lo + tx.hi), cy = 0.5f * (ty.lo + ty.hi);
    const float near = 0.99f * z.lo, far = 1.01f * z.hi;
    map = glm::frustum((cx - half) * near, (cx + half) * near, (cy - half) * near,
                       (cy + half) * near, near, far) *
          look;
    if (out.light_behind_camera) map = glm::scale(glm::mat4(1.0f), glm::vec3(1, 1, -1)) * map;
    f.tan_half_fov = half;
  }
  f.view_projection = map * to_pps;
  return f;
}

LightFrustum fit_lispsm(const Scene& scene, const std::vector<Bounds>& boxes,
                        const CameraView& camera, float n_scale, WarpInfo* info) {
  WarpInfo local;
  WarpInfo& out = info != nullptr ? *info : local;
  const glm::vec3 light = scene.light.center;
  // The light's own perspective: in its post-perspective space the light is
  // directional, along +z. It throws where shadow_map would.
  const LightFrustum base = fit_light_frustum(scene, light, false);
  if (base.view_projection == glm::mat4(1.0f)) return base;  // nothing casts
  std::vector<glm::vec4> planes = frustum_planes(camera.projection * camera.view);
  // Only what lies in front of the light's near plane has a place in its
  // post-perspective space (nothing behind it is shadowed: the lookup calls
  // points behind the light's plane lit).
  const glm::vec4 light_row(base.view[0][2], base.view[1][2], base.view[2][2], base.view[3][2]);
  planes.push_back(-light_row - glm::vec4(0.0f, 0.0f, 0.0f, 0.5f * base.near_plane));
  const std::vector<glm::vec3> body = visible_body(boxes, planes);
  if (body.empty()) return base;

  std::vector<glm::vec3> region, occluders;
  glm::vec3 centroid(0.0f);
  Range depth;
  for (const auto& p : body) {
    region.push_back(euclid(base.view_projection * glm::vec4(p, 1.0f)));
    centroid += p;
    depth.add(camera_depth(camera.view, p));
  }
  centroid /= float(body.size());
  for (const Mesh& m : scene.meshes)
    if (m.casts_shadow)
      for (const auto& p : m.positions) {
        const glm::vec4 h = base.view_projection * glm::vec4(p, 1.0f);
        if (h.w > 0.0f) occluders.push_back(euclid(h));
      }

  // The view direction at the body's centre, seen in the light's
  // post-perspective space, projected perpendicular to the light (+z).
  const glm::vec3 forward = camera_forward(camera.view);
  float diameter = 0.0f;
  for (const auto& p : body) diameter = std::max(diameter, glm::length(p - centroid));
  const float step = 1e-3f * std::max(diameter, 1e-6f);
  const glm::vec3 moved =
      euclid(base.view_projection * glm::vec4(centroid + step * forward, 1.0f)) -
      euclid(base.view_projection * glm::vec4(centroid, 1.0f));
  const glm::vec2 across(moved);

  // n_opt (Wimmer et al. 2004, section 5): (z_n + sqrt(z_n z_f)) / sin(gamma)
  // in world units, for a body of extent d_w along the projected view
  // direction. Its ratio to that extent sets the warp's shape, carried into
  // the light's post-perspective space.
  const glm::vec3 to_body = glm::normalize(centroid - light);
  const float sin_gamma = glm::length(glm::cross(forward, to_body));
  const float z_n = std::max(depth.lo, 1e-6f * std::max(depth.hi, 1e-6f));
  const float z_f = std::max(depth.hi, z_n);
  const glm::vec3 along_w = forward - glm::dot(forward, to_body) * to_body;
  Range extent_w;
  if (glm::length(along_w) > 0.0f)
    for (const auto& p : body) extent_w.add(glm::dot(p, glm::normalize(along_w)));
  const float ratio = n_scale * (z_n + std::sqrt(z_n * z_f)) /
                      (std::max(sin_gamma, 1e-6f) * std::max(extent_w.size(), 1e-12f));
  out.uniform = !(glm::length(across) > 1e-3f * glm::length(moved)) || !(ratio < 1e4f) ||
                extent_w.empty() || !(extent_w.size() > 0.0f);

  // A frame of the post-perspective space: y along the projected view
  // direction, z along the light.
  const glm::vec2 y_axis = out.uniform ? glm::vec2(0.0f, 1.0f) : glm::normalize(across);
  glm::mat4 rotate(1.0f);  // rows: x = (y_axis.y, -y_axis.x), y = y_axis, z
  rotate[0][0] = y_axis.y;
  rotate[1][0] = -y_axis.x;
  rotate[0][1] = y_axis.x;
  rotate[1][1] = y_axis.y;
  Range x, y;
  for (const auto& p : region) {
    const glm::vec3 r(rotate * glm::vec4(p, 1.0f));
    x.add(r.x);
    y.add(r.y);
  }

  glm::mat4 warp = rotate;  // frame coordinates, then the perspective (if any)
  if (!out.uniform) {
    // The perspective's centre stands n before the body's near side, looking
    // along +y; after the divide by w = y − cy it maps (x, y, z) to
    // ((x − cx)/w, −1/w, z/w): x and z shrink with distance, and −1/w is a
    // projective depth along y. Light rays (lines along z, at fixed x and
    // y) stay lines along z, in order.
    const float n = ratio * y.size();
    out.n = n;
    const float cx = 0.5f * (x.lo + x.hi), cy = y.lo - n;
    glm::mat4 perspective(0.0f);
    perspective[0][0] = 1.0f;  // X = x - cx·w
    perspective[3][0] = -cx;
    perspective[3][1] = -1.0f;  // Y = -w
    perspective[2][2] = 1.0f;   // H = z
    perspective[1][3] = 1.0f;   // W = y - cy·w
    perspective[3][3] = -cy;
    warp = perspective * rotate;
  }
  Range wx, wy, wz;
  for (const auto& p : region) {
    const glm::vec3 w = euclid(warp * glm::vec4(p, 1.0f));
    wx.add(w.x);
    wy.add(w.y);
    wz.add(w.z);
  }
  for (const auto& p : occluders) {
    const glm::vec4 h = warp * glm::vec4(p, 1.0f);
    if (h.w > 0.0f) wz.add(h.z / h.w);
  }
  LightFrustum f = base;
  f.view_projection = box_to_clip(wx, wy, wz) * warp * base.view_projection;
  return f;
}

}  // namespace sb::techniques::shadow_map
