// The skins of soft shadow maps for linear lights
// (shadow_map/linear_light_skins.h), without GL: one quad per depth
// discontinuity, on the plane through the light and the texels' shared
// side, from the occluder's depth (visibility 0) to the receiver's
// (visibility 1); a smooth slope has none, and the shared cliff rule
// (common/depth_cliffs.h) still finds a small plateau over it.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "depth_map_light.h"
#include "shadow_map/linear_light_skins.h"

namespace sb::techniques::shadow_map {
namespace {

using test::kSize;
using test::light;
using test::window;

TEST(LinearLightSkins, EachOutlineSideIsAQuadFromTheOccluderDownToTheReceiver) {
  // A 4×4-texel block at distance 4 over a floor at distance 8.
  std::vector<float> depth(kSize * kSize, window(8.0f));
  for (int y = 6; y < 10; ++y)
    for (int x = 6; x < 10; ++x) depth[size_t(y) * kSize + size_t(x)] = window(4.0f);
  std::vector<SkinVertex> skin;
  EXPECT_EQ(append_linear_light_skins(depth, kSize, light(), 0.002f, 100.0f, skin), 16u);
  ASSERT_EQ(skin.size(), 16u * 6u);
  for (size_t q = 0; q < skin.size(); q += 6) {
    int occluder = 0, receiver = 0;
    for (size_t i = q; i < q + 6; ++i) {
      const SkinVertex& v = skin[i];
      EXPECT_EQ(v.position.w, 1.0f);
      // Occluder ends at the block's distance, receiver ends on the floor.
      if (v.visibility == 0.0f) {
        ++occluder;
        EXPECT_NEAR(-v.position.z, 4.0f, 1e-4f);
      } else {
        ++receiver;
        EXPECT_EQ(v.visibility, 1.0f);
        EXPECT_NEAR(-v.position.z, 8.0f, 1e-3f);
      }
    }
    EXPECT_EQ(occluder, 3);
    EXPECT_EQ(receiver, 3);
    // The quad lies on a plane through the light: its receiver corners are
    // its occluder corners scaled by 2 from the light (at the origin).
    const glm::vec3 a(skin[q].position), c(skin[q + 2].position);
    const glm::vec3 normal = glm::cross(glm::vec3(skin[q + 1].position) - a, c - a);
    EXPECT_NEAR(glm::dot(glm::normalize(normal), glm::normalize(a)), 0.0f, 1e-4f);
    // Texels 6 to 9 of 16 span [-1, 1] at distance 4: each side is there.
    EXPECT_NEAR(std::max(std::fabs(a.x), std::fabs(a.y)), 1.0f, 1e-3f);  // a is an occluder end
  }
}

TEST(LinearLightSkins, ASmoothSlopeHasNoSkinAndAPlateauOverItHasOne) {
  std::vector<float> depth(kSize * kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      depth[size_t(y) * kSize + size_t(x)] = window(3.0f + 0.12f * float(x));
  std::vector<SkinVertex> skin;
  EXPECT_EQ(append_linear_light_skins(depth, kSize, light(), 0.002f, 100.0f, skin), 0u);
  // A 2×2 plateau 1% nearer: its 8 sides, and the 2 steps inside it (each
  // side of those is extrapolated from a slope texel: a 2-texel plateau is
  // too narrow to continue), as the cliff rule finds them for
  // hybrid_reconstruction too.
  for (int y = 7; y < 9; ++y)
    for (int x = 7; x < 9; ++x)
      depth[size_t(y) * kSize + size_t(x)] = window(0.99f * (3.0f + 0.12f * float(x)));
  EXPECT_EQ(append_linear_light_skins(depth, kSize, light(), 0.002f, 100.0f, skin), 10u);
  EXPECT_EQ(skin.size(), 10u * 6u);
}

TEST(LinearLightSkins, WithNothingBehindTheSkinReachesPastEveryReceiver) {
  std::vector<float> depth(kSize * kSize, 1.0f);
  depth[size_t(8) * kSize + 8] = window(4.0f);
  std::vector<SkinVertex> skin;
  EXPECT_EQ(append_linear_light_skins(depth, kSize, light(), 0.002f, 50.0f, skin), 4u);
  for (const SkinVertex& v : skin) {
    if (v.visibility == 1.0f) {
      EXPECT_NEAR(glm::length(glm::vec3(v.position)), 50.0f, 1e-3f);
    }
  }
}

}  // namespace
}  // namespace sb::techniques::shadow_map
