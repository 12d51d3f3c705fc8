#include <gtest/gtest.h>

#include "core/scene_types.h"
#include "scene_type_test_util.h"
#include "scenes/sphere_grid.h"

namespace sb {

using core::AnalyticShape;
using core::Bounds;
using core::Mesh;
using core::Scene;

namespace {

using test::build_scene_type;

TEST(SphereGrid, DefaultTriangleCounts) {
  const Scene s = build_scene_type("sphere_grid", nlohmann::json::object());
  ASSERT_EQ(s.meshes.size(), 82u);                // 81 spheres + ground
  EXPECT_EQ(s.meshes[0].triangle_count(), 760u);  // 20 slices × 20 stacks
  EXPECT_EQ(s.triangle_count(), 81u * 760u + 2u);
  EXPECT_EQ(s.caster_triangle_count(), 81u * 760u);
  EXPECT_FALSE(s.meshes.back().casts_shadow);
}

TEST(SphereGrid, ScaleParametersSweepTriangleCount) {
  const Scene s =
      build_scene_type("sphere_grid", {{"grid", 3}, {"layers", 2}, {"slices", 8}, {"stacks", 5}});
  EXPECT_EQ(s.caster_triangle_count(), 3u * 3u * 2u * (2u * 8u * 4u));
  EXPECT_EQ(s.meshes.size(), 19u);
}

TEST(SphereGrid, SpheresFloatAboveTheGroundUnderTheLight) {
  const Scene s = build_scene_type("sphere_grid", nlohmann::json::object());
  const Bounds casters = s.caster_bounds();
  EXPECT_GT(casters.lo.y, 0.0f);  // nothing touches or pierces the ground
  EXPECT_GT(s.light.center.y, casters.hi.y);
  EXPECT_NEAR(s.light.width(), 2.0f, 1e-5f);
  EXPECT_NEAR(glm::dot(s.light.half_u, s.light.direction()), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::dot(s.light.half_v, s.light.direction()), 0.0f, 1e-5f);
}

TEST(SphereGrid, AnalyticGivesEverySphereItsExactShape) {
  for (const Mesh& m : build_scene_type("sphere_grid", nlohmann::json::object()).meshes)
    EXPECT_FALSE(m.analytic.has()) << m.name;  // off by default
  const Scene s = build_scene_type(
      "sphere_grid", {{"grid", 2}, {"layers", 2}, {"analytic", true}, {"radius", 0.4}});
  EXPECT_EQ(s.analytic_caster_count(), 8u);
  for (const Mesh& m : s.meshes) {
    if (!m.casts_shadow) {
      EXPECT_FALSE(m.analytic.has()) << m.name;  // the ground keeps its triangles
      continue;
    }
    ASSERT_EQ(m.analytic.kind, AnalyticShape::Kind::Sphere) << m.name;
    EXPECT_FLOAT_EQ(m.analytic.radius, 0.4f);
    for (const glm::vec3& p : m.positions)  // the tessellation is inscribed
      EXPECT_NEAR(glm::distance(p, m.analytic.center), 0.4f, 1e-5f) << m.name;
  }
}

TEST(UvSphere, WindsCounterClockwiseOutwards) {
  const glm::vec3 c(1, 2, 3);
  const Mesh m = make_uv_sphere("s", c, 0.5f, 12, 7);
  ASSERT_EQ(m.triangle_count(), 2u * 12u * 6u);
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const glm::vec3 a = m.positions[m.indices[3 * t]];
    const glm::vec3 b = m.positions[m.indices[3 * t + 1]];
    const glm::vec3 d = m.positions[m.indices[3 * t + 2]];
    const glm::vec3 n = glm::cross(b - a, d - a);
    EXPECT_GT(glm::dot(n, (a + b + d) / 3.0f - c), 0.0f) << "triangle " << t;
  }
  for (size_t v = 0; v < m.positions.size(); ++v)
    EXPECT_NEAR(glm::length(m.positions[v] - c), 0.5f, 1e-5f);
}

}  // namespace
}  // namespace sb
