#include <gtest/gtest.h>

#include "core/scene_types.h"
#include "plan/need_resolution.h"
#include "scene_type_test_util.h"
#include "scenes/leaf.h"
#include "scenes/topology.h"

namespace sb {

using core::Bounds;
using core::Mesh;
using core::sample_alpha;
using core::Scene;
using core::TextureImage;
using plan::Derive;
using plan::resolve_needs;
using plugin::Needs;
using plugin::TechniqueInfo;

namespace {

using test::build_scene_type;

TEST(Foliage, WoodIsClosedLeavesAreOpenAndMasked) {
  const Scene s = build_scene_type(
      "foliage",
      {{"trees", 2}, {"depth", 2}, {"branches", 3}, {"leaves_per_branch", 4}, {"segments", 6}});
  ASSERT_EQ(s.meshes.size(), 4u);  // two trees' wood, the leaves, the ground
  const size_t branches_per_tree = 1 + 3 + 9;
  for (int t = 0; t < 2; ++t) {
    const Mesh& wood = s.meshes[size_t(t)];
    EXPECT_EQ(wood.name, "tree_" + std::to_string(t) + "/wood");
    EXPECT_EQ(wood.triangle_count(), branches_per_tree * 4 * 6);  // capped 6-sided cylinders
    EXPECT_TRUE(analyse_topology(wood).closed()) << wood.name;
  }
  const Mesh& leaves = s.meshes[2];
  EXPECT_EQ(leaves.name, "leaves");
  EXPECT_EQ(leaves.triangle_count(),
            2u * 9u * 4u * 2u);  // 2 trees × 9 twigs × 4 leaves × 2 triangles
  EXPECT_TRUE(leaves.alpha_tested());
  EXPECT_TRUE(leaves.double_sided);
  EXPECT_TRUE(leaves.casts_shadow);
  EXPECT_EQ(analyse_topology(leaves).boundary_edges, 4u * 2u * 9u * 4u);  // every quad edge
  EXPECT_FALSE(s.meshes[3].casts_shadow);
  ASSERT_EQ(s.textures.size(), 1u);

  // The skip reason names the leaves and their boundary edges.
  TechniqueInfo volume{"shadow_volume",
                       "f",
                       "",
                       Needs{plugin::need::kClosedCasters, plugin::need::kOpaqueCasters},
                       {},
                       nullptr};
  EXPECT_EQ(resolve_needs(s, {&volume}, nullptr, Derive::Decide).skip_reason[0],
            "shadow_volume needs closed casters: mesh 'leaves' has 288 boundary edges");
}

TEST(Foliage, SameSeedSameTreesOtherSeedOtherTrees) {
  const Scene a = build_scene_type("foliage", {{"seed", 7}}),
              b = build_scene_type("foliage", {{"seed", 7}}),
              c = build_scene_type("foliage", {{"seed", 8}});
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t i = 0; i < a.meshes.size(); ++i)
    EXPECT_EQ(a.meshes[i].positions, b.meshes[i].positions);
  EXPECT_NE(a.meshes[0].positions, c.meshes[0].positions);
}

TEST(Foliage, TreesStandOnTheGroundUnderTheLight) {
  const Scene s = build_scene_type("foliage", nlohmann::json::object());
  const Bounds b = s.caster_bounds();
  EXPECT_GE(b.lo.y, -0.2f);  // roots may dip a little below
  EXPECT_GT(s.light.center.y, b.hi.y);
  EXPECT_GT(b.hi.y, 1.5f);
}

TEST(LeafTexture, HasHolesAndBlade) {
  const TextureImage t = make_leaf_texture(64, 1);
  const double f = opaque_fraction(t, 0.5f);
  EXPECT_GT(f, 0.3);
  EXPECT_LT(f, 0.7);
  EXPECT_EQ(sample_alpha(t, {0.5f, 0.5f}), 1.0f);   // the blade's middle
  EXPECT_EQ(sample_alpha(t, {0.02f, 0.5f}), 0.0f);  // beside it
  EXPECT_EQ(sample_alpha(t, {1.5f, 0.5f}), 1.0f);   // wraps around
  EXPECT_EQ(sample_alpha(t, {-0.5f, 0.5f}), 1.0f);
}

}  // namespace
}  // namespace sb
