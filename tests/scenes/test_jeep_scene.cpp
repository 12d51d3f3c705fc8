#include <gtest/gtest.h>

#include <cmath>

#include "core/scene_types.h"
#include "scenes/topology.h"

namespace sb {
namespace {

Scene build(const nlohmann::json& given) {
  const SceneType* t = find_scene_type("jeep");
  return t->build(resolve_params(t->params, given, "test", "/params"));
}

TEST(JeepScene, OneJeepIsAFewThousandClosedTriangles) {
  const Scene s = build({{"count", 1}});
  EXPECT_EQ(s.caster_triangle_count(), 3620u);
  EXPECT_GT(s.meshes.size(), 15u);  // body, bonnet, wheels, tyres, rims, bumpers, ...
  for (const auto& m : s.meshes)
    if (m.casts_shadow) {
      EXPECT_TRUE(analyse_topology(m).closed()) << m.name;
    }
}

TEST(JeepScene, CountScalesTheCastersAndTheSetStaysInFrame) {
  for (int count : {2, 8, 32}) {
    const Scene s = build({{"count", count}});
    EXPECT_EQ(s.caster_triangle_count(), size_t(count) * 3620u) << count;
    const Bounds b = s.caster_bounds();
    EXPECT_GE(b.lo.y, -1e-4f) << count;  // nothing below the ground
    EXPECT_GT(s.light.center.y, b.hi.y) << count;
    // Every corner of the set projects inside the camera's 4:3 view.
    const glm::mat4 vp = s.camera.projection(4.0f / 3.0f) * s.camera.view();
    for (int i = 0; i < 8; ++i) {
      const glm::vec4 c = vp * glm::vec4((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y,
                                         (i & 4) ? b.hi.z : b.lo.z, 1.0f);
      ASSERT_GT(c.w, 0.0f);
      EXPECT_LE(std::abs(c.x / c.w), 1.0f) << count << " corner " << i;
      EXPECT_LE(std::abs(c.y / c.w), 1.0f) << count << " corner " << i;
    }
  }
}

}  // namespace
}  // namespace sb
