// The `standing` scene (scenes/standing.cpp): a closed box on the ground
// whose shadow from the light's centre ends where the docs' formula says,
// framed from its foot to the tip's penumbra, and its bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "core/scene_types.h"
#include "scene_type_test_util.h"
#include "scenes/topology.h"

namespace sb {

using core::Bounds;
using core::find_scene_type;
using core::InputError;
using core::Mesh;
using core::resolve_params;
using core::Scene;
using core::SceneType;

namespace {

using test::build_scene_type;
using test::ndc_of;

// Where the ray from the light's centre through p meets the ground y = 0.
glm::vec3 ground_hit(const Scene& s, glm::vec3 p) {
  const glm::vec3 l = s.light.center;
  return l + (p - l) * (l.y / (l.y - p.y));
}

TEST(StandingScene, AClosedBoxOnTheGroundWhoseShadowTipIsWhereTheDocsSay) {
  const Scene s =
      build_scene_type("standing", {{"height", 1.8}, {"width", 0.5}, {"light_offset", 2.5}});
  ASSERT_EQ(s.meshes.size(), 2u);
  const Mesh& box = s.meshes[0];
  EXPECT_EQ(box.name, "occluder");
  EXPECT_TRUE(box.casts_shadow);
  EXPECT_TRUE(analyse_topology(box).closed());
  Bounds b;
  for (const auto& p : box.positions) b.extend(p);
  EXPECT_FLOAT_EQ(b.lo.y, 0.0f);  // it stands on the ground: a contact line
  EXPECT_FLOAT_EQ(b.hi.y, 1.8f);
  // The far top edge's shadow from the light's centre, by ray casting,
  // against the formula in standing.cpp.
  const float tip = ground_hit(s, {0.25f, 1.8f, 0.0f}).x;
  EXPECT_NEAR(tip, -2.5f + (2.5f + 0.25f) * 6.0f / (6.0f - 1.8f), 1e-4f);
  // The light faces straight down from its height.
  EXPECT_FLOAT_EQ(s.light.center.y, 6.0f);
  EXPECT_NEAR(s.light.direction().y, -1.0f, 1e-6f);
  // Framed: the foot, both ends of the shadow and the tip's penumbra.
  const float penumbra = 1.0f * 1.8f / (6.0f - 1.8f);
  for (const glm::vec3 p :
       {glm::vec3(0.25f, 0.0f, 0.25f), glm::vec3(0.25f, 0.0f, -0.25f),
        glm::vec3(tip + penumbra, 0.0f, 0.0f), glm::vec3(tip, 0.0f, 0.5f * penumbra + 0.3f)}) {
    const glm::vec3 ndc = ndc_of(s, p);
    EXPECT_LT(std::fabs(ndc.x), 1.0f) << p.x << " " << p.z;
    EXPECT_LT(std::fabs(ndc.y), 1.0f) << p.x << " " << p.z;
  }
}

TEST(StandingScene, ALightBelowTheBoxsTopIsBadInputNamingTheParameter) {
  const SceneType* t = find_scene_type("standing");
  const auto bad = resolve_params(t->params, {{"height", 3.0}, {"light_height", 2.0}}, "x", "");
  const auto [param, problem] = t->check(bad);
  EXPECT_EQ(param, "light_height");
  EXPECT_NE(problem.find("greater than the box's height (3)"), std::string::npos) << problem;
  try {
    t->build(bad);
    FAIL() << "built a box reaching past its light";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/params/light_height"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sb
