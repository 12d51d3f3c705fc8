// The sun's single orthographic map (fit_sun_frustum): its box holds every
// caster across the light and every caster and receiver along it, it fits
// the casters (not a ground that reaches past them), and a caster outside
// the receivers' extent is in it. Checked against the scene's own vertices
// and closed forms of the box for a sun straight overhead.
#include <gtest/gtest.h>

#include <cmath>

#include "common/light_frustum.h"
#include "core/scene_types.h"
#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"

namespace sb::techniques {
namespace {

using core::Scene;

// A ground of half size 10, a box on it, and a plate floating past the
// ground's edge (x 11..13, y 6) whose shadow, under a sun from +x at 45°,
// falls on the ground (x 5..7).
Scene plate_past_the_ground(const glm::vec3& to_sun) {
  Scene s;
  s.name = "sun_fit";
  s.meshes.push_back(make_ground_plane("ground", {0.0f, 0.0f, 0.0f}, 10.0f));
  s.meshes.push_back(make_box("box", {-2.0f, 1.0f, 0.0f}, {1.0f, 1.0f, 1.0f}));
  s.meshes.push_back(make_box("plate", {12.0f, 6.0f, 0.0f}, {1.0f, 0.05f, 1.0f}));
  s.light = core::make_sun_light(to_sun, {0.0f, 0.0f, 0.0f}, 0.00925f, 50.0f);
  return s;
}

glm::vec3 ndc(const LightFrustum& f, const glm::vec3& p) {
  const glm::vec4 c = f.view_projection * glm::vec4(p, 1.0f);
  return glm::vec3(c) / c.w;
}

TEST(SunFrustum, HoldsEveryCasterAcrossAndEveryPointAlongTheLight) {
  for (const glm::vec3 to_sun : {glm::vec3(1, 1, 0), glm::vec3(0.3f, 1.0f, -0.5f),
                                 glm::vec3(0, 1, 0), glm::vec3(-2.0f, 0.4f, 1.0f)}) {
    const Scene s = plate_past_the_ground(to_sun);
    const LightFrustum f = fit_sun_frustum(s);
    ASSERT_TRUE(f.orthographic);
    EXPECT_GT(f.near_plane, 0.0f);
    for (const auto& m : s.meshes)
      for (const glm::vec3& p : m.positions) {
        const glm::vec3 c = ndc(f, p);
        // Every caster and every receiver has a depth inside the map's range.
        EXPECT_GE(c.z, -1.0f) << m.name;
        EXPECT_LE(c.z, 1.0f) << m.name;
        if (!m.casts_shadow) continue;
        EXPECT_LE(std::fabs(c.x), 1.0f) << m.name;
        EXPECT_LE(std::fabs(c.y), 1.0f) << m.name;
      }
    // Window depth is linear in distance along the light (orthographic).
    const glm::vec3 a(0.0f), b = a - 3.0f * glm::normalize(to_sun);
    const float per_unit = (ndc(f, b).z - ndc(f, a).z) / 3.0f;
    EXPECT_NEAR(per_unit, 2.0f / (f.far_plane - f.near_plane), 1e-5f);
  }
}

// A caster whose shadow falls on the ground while it stands past the
// ground's edge: the ground point under its shadow and the plate's point
// above it land on the same map texel, and the plate is nearer the sun.
TEST(SunFrustum, ACasterPastTheReceiversShadowsThemInTheMap) {
  const Scene s = plate_past_the_ground({1.0f, 1.0f, 0.0f});
  const LightFrustum f = fit_sun_frustum(s);
  const glm::vec3 on_plate(12.0f, 5.95f, 0.0f), under(12.0f - 5.95f, 0.0f, 0.0f);
  const glm::vec3 a = ndc(f, on_plate), b = ndc(f, under);
  ASSERT_LE(std::fabs(a.x), 1.0f);
  ASSERT_LE(std::fabs(a.y), 1.0f);
  EXPECT_NEAR(a.x, b.x, 1e-4f);
  EXPECT_NEAR(a.y, b.y, 1e-4f);
  EXPECT_LT(a.z, b.z);
}

// Sun overhead: the map is the casters' square across x/z (the box from
// x = -3 to the plate's x = 13, 16 wide), grown by the disk's reach over the
// depth range (the plate's top at 6.05 down to the ground at 0:
// 6.05·tan(α/2)) and 1%, not the ground's 20.
TEST(SunFrustum, FitsTheCastersNotTheGroundUnderThem) {
  const Scene s = plate_past_the_ground({0.0f, 1.0f, 0.0f});
  const LightFrustum f = fit_sun_frustum(s);
  const float reach = 6.05f * std::tan(0.5f * 0.00925f);
  EXPECT_NEAR(f.half_extent, 0.5f * (16.0f + 2.0f * reach) * 1.01f, 1e-3f);
  EXPECT_NEAR(f.texel_world(1024), 2.0f * f.half_extent / 1024.0f, 1e-7f);
  // Its depth range: the scene's box along the light (6.05 deep) and 1% each
  // side (and 1e-4 of the scene's radius).
  EXPECT_NEAR(f.far_plane - f.near_plane, 6.05f * 1.02f, 5e-3f);
}

TEST(SunFrustum, NoCasterLeavesEveryPointLit) {
  Scene s = plate_past_the_ground({1.0f, 1.0f, 0.0f});
  s.meshes.resize(1);  // the ground alone
  EXPECT_EQ(fit_sun_frustum(s).view_projection, glm::mat4(1.0f));
}

TEST(SunFrustum, TheSingleMapFitIsTheSunsUnderTheSunOnly) {
  Scene s = plate_past_the_ground({1.0f, 1.0f, 0.0f});
  EXPECT_TRUE(fit_single_map_frustum(s).orthographic);
  s.light = core::make_area_light({0.0f, 20.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, 1.0f, 1.0f);
  EXPECT_FALSE(fit_single_map_frustum(s).orthographic);
}

}  // namespace
}  // namespace sb::techniques
