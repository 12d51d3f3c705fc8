// The extended light map's pass (shadow_map/extended_light_map.h) on the
// `standing` scene: the light channel holds the analytic irradiance of the
// ground each texel sees, the alpha channel its distance along the light's
// axis in 8 bits, and the light channel written in its own pass gives the
// same texels as in the shadow channel's (what makes the single-pass saving
// a fair comparison).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "common/light_frustum.h"
#include "core/scene_types.h"
#include "gl/context.h"
#include "gl/debug.h"
#include "gl/gpu_scene.h"
#include "shadow_map/extended_light_map.h"

namespace sb::techniques::shadow_map {

using core::find_scene_type;
using core::Mesh;
using core::resolve_params;
using core::Scene;
using core::SceneType;
using gl::GpuScene;
using gl::MeshDrawFlags;

namespace {

constexpr int kSize = 128;

struct Channels {
  std::vector<std::uint8_t> color;  // RGBA8
  std::vector<float> depth;
};

class ExtendedLightMapPass : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = gl::create_context(gl::Backend::OSMesa);
    const SceneType* t = find_scene_type("standing");
    ASSERT_NE(t, nullptr);
    scene_ = t->build(resolve_params(t->params, nlohmann::json::object(), "test", "/params"));
    // The box is closed; the ground has nothing behind it (it is in the map).
    std::vector<MeshDrawFlags> flags;
    for (const Mesh& m : scene_.meshes) flags.push_back({m.casts_shadow, !m.casts_shadow});
    gpu_ = std::make_unique<GpuScene>(scene_, std::vector<std::vector<uint32_t>>{}, flags);
    frustum_ = fit_light_frustum(scene_, scene_.light.center);
  }

  Channels render(ShadowChannel shadow, LightChannel light) {
    ExtendedLightMapSettings s;
    s.size = kSize;
    s.shadow = shadow;
    s.light = light;
    ExtendedLightMap map(s);
    map.render_shadow_channel(*gpu_, frustum_);
    if (light == LightChannel::SeparatePass) map.render_light_channel(*gpu_, frustum_);
    gl::throw_if_errors("extended light map test");
    Channels c;
    c.color.resize(size_t(kSize) * kSize * 4);
    c.depth.resize(size_t(kSize) * kSize);
    glGetTextureImage(map.color(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(c.color.size()),
                      c.color.data());
    glGetTextureImage(map.depth(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                      GLsizei(c.depth.size() * sizeof(float)), c.depth.data());
    return c;
  }

  // The world point texel (x, y) sees at window depth d.
  glm::vec3 world_at(int x, int y, float d) const {
    const glm::vec4 ndc((float(x) + 0.5f) / kSize * 2.0f - 1.0f,
                        (float(y) + 0.5f) / kSize * 2.0f - 1.0f, d * 2.0f - 1.0f, 1.0f);
    const glm::vec4 w = glm::inverse(frustum_.view_projection) * ndc;
    return glm::vec3(w) / w.w;
  }

  std::unique_ptr<gl::Context> context_;
  Scene scene_;
  std::unique_ptr<GpuScene> gpu_;
  LightFrustum frustum_;
};

TEST_F(ExtendedLightMapPass, HoldsTheGroundsIrradianceAndItsEightBitDistance) {
  const Channels c = render(ShadowChannel::Alpha8, LightChannel::SamePass);
  const glm::vec3 light = scene_.light.center;
  int ground = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const size_t i = size_t(y) * kSize + size_t(x);
      if (c.depth[i] >= 1.0f) continue;
      const glm::vec3 p = world_at(x, y, c.depth[i]);
      if (std::fabs(p.y) > 1e-3f) continue;  // the box
      ++ground;
      const float r = glm::length(light - p);
      const float cos_theta = (light.y - p.y) / r;
      const float ratio = frustum_.near_plane / r;
      const float irradiance = cos_theta * ratio * ratio;
      const float along = -(frustum_.view * glm::vec4(p, 1.0f)).z;
      const float depth01 =
          (along - frustum_.near_plane) / (frustum_.far_plane - frustum_.near_plane);
      EXPECT_NEAR(c.color[i * 4 + 0] / 255.0f, irradiance, 1.0f / 255.0f) << x << " " << y;
      EXPECT_EQ(c.color[i * 4 + 0], c.color[i * 4 + 1]);
      EXPECT_NEAR(c.color[i * 4 + 3], depth01 * 255.0f, 0.51f) << x << " " << y;
    }
  EXPECT_GT(ground, kSize * kSize / 4);
}

TEST_F(ExtendedLightMapPass, ALightChannelOfItsOwnPassWritesTheSameTexels) {
  for (const ShadowChannel s :
       {ShadowChannel::Alpha8, ShadowChannel::Depth24, ShadowChannel::Depth32f}) {
    const Channels one = render(s, LightChannel::SamePass);
    const Channels two = render(s, LightChannel::SeparatePass);
    EXPECT_EQ(one.color, two.color) << int(s);
    EXPECT_EQ(one.depth, two.depth) << int(s);
    // Without a light channel the rgb stay as cleared (no light), the
    // shadow channel is the same.
    const Channels none = render(s, LightChannel::None);
    int lit = 0;
    for (size_t i = 0; i < none.depth.size(); ++i) {
      EXPECT_EQ(none.color[i * 4], 0);
      EXPECT_EQ(none.color[i * 4 + 3], one.color[i * 4 + 3]);
      lit += one.color[i * 4] > 0 ? 1 : 0;
    }
    EXPECT_EQ(none.depth, one.depth);
    EXPECT_GT(lit, kSize * kSize / 4);
  }
}

}  // namespace
}  // namespace sb::techniques::shadow_map
