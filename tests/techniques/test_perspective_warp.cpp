// PSM's and LiSPSM's warps (shadow_map/perspective_warp.h) on the
// long_ground scene, without GL: every ray from the light's centre must stay
// a line along the map's depth axis with depth growing away from the light
// (so one depth comparison is the hard shadow's test), whatever side of the
// camera the light is on, and the map's texels must be denser near the
// camera than a uniform map's, and sparser far away.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/convex_body.h"
#include "core/scene_types.h"
#include "shadow_map/perspective_warp.h"

namespace sb::techniques::shadow_map {

using core::find_scene_type;
using core::Mesh;
using core::resolve_params;
using core::Scene;
using core::SceneType;

namespace {

constexpr float kAspect = 4.0f / 3.0f;

Scene long_ground(const std::string& light) {
  const SceneType* t = find_scene_type("long_ground");
  EXPECT_NE(t, nullptr);
  return t->build(resolve_params(t->params, {{"light", light}}, "test", "/params"));
}

CameraView camera_of(const Scene& s) { return {s.camera.view(), s.camera.projection(kAspect)}; }

// Where the camera ray through NDC (x, y) meets the ground y = 0.
glm::vec3 ground_at(const Scene& s, float x, float y) {
  const glm::mat4 inverse = glm::inverse(s.camera.projection(kAspect) * s.camera.view());
  const glm::vec4 a = inverse * glm::vec4(x, y, -1.0f, 1.0f);
  const glm::vec4 b = inverse * glm::vec4(x, y, 1.0f, 1.0f);
  const glm::vec3 p = glm::vec3(a) / a.w, q = glm::vec3(b) / b.w;
  return p + (q - p) * (p.y / (p.y - q.y));
}

glm::vec4 clip(const LightFrustum& f, const glm::vec3& p) {
  return f.view_projection * glm::vec4(p, 1.0f);
}

LightFrustum fit(const std::string& technique, const Scene& s, WarpInfo* info = nullptr,
                 float n_scale = 1.0f) {
  return technique == "psm" ? fit_psm(s, mesh_boxes(s), camera_of(s), info)
                            : fit_lispsm(s, mesh_boxes(s), camera_of(s), n_scale, info);
}

TEST(PerspectiveWarp, KeepsEveryLightRayALineAlongTheDepthAxisInOrder) {
  for (const std::string light : {"side", "behind", "front"})
    for (const std::string technique : {"psm", "lispsm"}) {
      const Scene s = long_ground(light);
      const LightFrustum f = fit(technique, s);
      int tested = 0;
      for (int i = 0; i < 7; ++i)
        for (int j = 0; j < 4; ++j) {
          const float x = -0.9f + 0.3f * float(i), y = -0.95f + 0.25f * float(j);
          const glm::vec3 receiver = ground_at(s, x, y);
          const glm::vec4 r = clip(f, receiver);
          ASSERT_GT(r.w, 0.0f) << light << " " << technique;
          const glm::vec3 rn = glm::vec3(r) / r.w;
          // The visible ground lies inside the map.
          EXPECT_LE(std::fabs(rn.x), 1.0f + 1e-4f) << light << " " << technique;
          EXPECT_LE(std::fabs(rn.y), 1.0f + 1e-4f) << light << " " << technique;
          EXPECT_LE(std::fabs(rn.z), 1.0f + 1e-4f) << light << " " << technique;
          for (const float t : {0.3f, 0.6f, 0.9f, 0.99f}) {
            const glm::vec3 between = s.light.center + t * (receiver - s.light.center);
            const glm::vec4 c = clip(f, between);
            if (!(c.w > 0.0f)) continue;  // behind PSM's virtual camera: no caster there
            const glm::vec3 cn = glm::vec3(c) / c.w;
            EXPECT_NEAR(cn.x, rn.x, 2e-4f) << light << " " << technique << " t " << t;
            EXPECT_NEAR(cn.y, rn.y, 2e-4f) << light << " " << technique << " t " << t;
            EXPECT_LT(cn.z, rn.z) << light << " " << technique << " t " << t;
            ++tested;
          }
        }
      EXPECT_GE(tested, 60) << light << " " << technique;
      // With the light behind, every post can shadow the view, and PSM's
      // virtual camera keeps them all in front of the map's eye (w > 0):
      // none is mirrored into it.
      if (technique == "psm" && light == "behind") {
        for (const Mesh& m : s.meshes) {
          if (!m.casts_shadow) continue;
          for (const auto& p : m.positions) EXPECT_GT(clip(f, p).w, 0.0f) << m.name;
        }
      }
    }
}

TEST(PerspectiveWarp, PsmInvertsDepthAndMovesTheCameraBackOnlyForALightBehindIt) {
  WarpInfo side, behind;
  const Scene side_scene = long_ground("side"), behind_scene = long_ground("behind");
  fit_psm(side_scene, mesh_boxes(side_scene), camera_of(side_scene), &side);
  fit_psm(behind_scene, mesh_boxes(behind_scene), camera_of(behind_scene), &behind);
  EXPECT_FALSE(side.light_behind_camera);
  EXPECT_EQ(side.virtual_shift, 0.0f);  // the post behind the camera cannot shadow the view
  EXPECT_TRUE(behind.light_behind_camera);
  // The first pair of posts stands 1 behind the eye; the nearest visible
  // ground is about 2.5 ahead.
  EXPECT_GT(behind.virtual_shift, 2.0f);
  EXPECT_LT(behind.virtual_shift, 6.0f);
}

// Map texels per unit of ground area at a ground point: |det| of the
// Jacobian of the map's (x, y) over the ground's (x, z).
double density(const LightFrustum& f, const glm::vec3& p) {
  const float h = 1e-3f;
  const auto map = [&](const glm::vec3& q) {
    const glm::vec4 c = clip(f, q);
    return glm::dvec2(c.x / c.w, c.y / c.w);
  };
  const glm::dvec2 dx = (map(p + glm::vec3(h, 0, 0)) - map(p - glm::vec3(h, 0, 0))) / (2.0 * h);
  const glm::dvec2 dz = (map(p + glm::vec3(0, 0, h)) - map(p - glm::vec3(0, 0, h))) / (2.0 * h);
  return std::fabs(dx.x * dz.y - dx.y * dz.x);
}

TEST(PerspectiveWarp, SpendsTexelsNearTheCameraThatAUniformMapSpendsFarAway) {
  const Scene s = long_ground("side");
  const LightFrustum uniform = fit_light_frustum(s, s.light.center);
  // Near the image's bottom, and near the strip's far end (z = -60).
  const glm::vec3 near = ground_at(s, 0.0f, -0.9f), far(0.0f, 0.0f, -54.0f);
  for (const std::string technique : {"psm", "lispsm"}) {
    const LightFrustum f = fit(technique, s);
    const double near_gain = density(f, near) / density(uniform, near);
    const double far_gain = density(f, far) / density(uniform, far);
    std::printf("%-6s texel density over the uniform map's: near %.2f, far %.2f\n",
                technique.c_str(), near_gain, far_gain);
    EXPECT_GT(near_gain, 2.0) << technique;
    EXPECT_LT(far_gain, 1.0) << technique;
  }
  // LiSPSM's n_scale moves it towards the uniform map.
  double previous = 1e30;
  for (const float n_scale : {1.0f, 10.0f, 1000.0f}) {
    const double gain = density(fit("lispsm", s, nullptr, n_scale), near) / density(uniform, near);
    EXPECT_LT(gain, previous) << n_scale;
    previous = gain;
  }
}

// The camera half way to the light, looking where it looks (the stress
// suite's view_along_light): sin γ ≈ 0, n_opt grows without bound, and
// LiSPSM must spend its texels as the uniform map does, nowhere 2× more or
// less.
TEST(PerspectiveWarp, LispsmLookingAlongTheLightIsTheUniformMap) {
  const SceneType* t = find_scene_type("sphere_grid");
  ASSERT_NE(t, nullptr);
  Scene s = t->build(resolve_params(t->params, {{"grid", 3}}, "test", "/params"));
  s.camera.eye = 0.5f * s.light.center;
  s.camera.target = s.light.target;
  WarpInfo info;
  const LightFrustum f = fit_lispsm(s, mesh_boxes(s), camera_of(s), 1.0f, &info);
  const LightFrustum uniform = fit_light_frustum(s, s.light.center);
  for (const glm::vec3 p :
       {glm::vec3(0.0f), glm::vec3(2.0f, 0.0f, 2.0f), glm::vec3(-2.0f, 0.0f, -2.0f)}) {
    const double gain = density(f, p) / density(uniform, p);
    EXPECT_GT(gain, 0.5) << info.n;
    EXPECT_LT(gain, 2.0) << info.n;
  }
}

}  // namespace
}  // namespace sb::techniques::shadow_map
