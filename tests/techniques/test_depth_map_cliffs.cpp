// Shadow volumes reconstructed from a depth map (shadow_volume/
// depth_map_cliffs.h), without GL: counted as a z-pass stencil counts them
// (+1 for each face a ray from the camera enters through, −1 for each it
// leaves through, before the point), a point behind an occluder block is
// inside once and a point beside it is not; a smooth slope is no cliff,
// however steep, and a small plateau over it is.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "depth_map_light.h"
#include "shadow_volume/depth_map_cliffs.h"

namespace sb::techniques::shadow_volume {
namespace {

using test::kSize;
using test::light;
using test::window;

// Signed crossings of the segment from `from` to `to` with the triangles:
// +1 through a face turned towards `from`, −1 through one turned away.
int count(const std::vector<glm::vec4>& triangles, glm::vec3 from, glm::vec3 to) {
  int n = 0;
  const glm::vec3 d = to - from;
  for (size_t i = 0; i + 2 < triangles.size(); i += 3) {
    const glm::vec3 a(triangles[i]), b(triangles[i + 1]), c(triangles[i + 2]);
    const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
    const float det = glm::dot(e1, p);
    if (std::fabs(det) < 1e-12f) continue;
    const glm::vec3 s = from - a;
    const float u = glm::dot(s, p) / det;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(d, q) / det, t = glm::dot(e2, q) / det;
    if (u < 0.0f || v < 0.0f || u + v > 1.0f || t <= 0.0f || t >= 1.0f) continue;
    n += glm::dot(glm::cross(e1, e2), d) < 0.0f ? 1 : -1;
  }
  return n;
}

TEST(DepthMapCliffs, APointBehindABlockIsInsideOnceAndOneBesideItIsNot) {
  // A 4×4-texel block at distance 4, nothing else: 16 sides of outline.
  std::vector<float> depth(kSize * kSize, 1.0f);
  for (int y = 6; y < 10; ++y)
    for (int x = 6; x < 10; ++x) depth[size_t(y) * kSize + size_t(x)] = window(4.0f);
  std::vector<glm::vec4> triangles;
  EXPECT_EQ(append_depth_map_cliffs(depth, kSize, light(), 0.002f, 100.0f, triangles), 16u);
  for (const auto& v : triangles) EXPECT_EQ(v.w, 1.0f);
  // Texels 6 to 9 of 16 span x, y in [-z/4, z/4] at distance z: the block
  // covers [-1, 1] at distance 4, and its shadow [-2, 2] at distance 8.
  const glm::vec3 camera(6.0f, 1.0f, -7.0f);  // beside the shadow, below the block
  EXPECT_EQ(count(triangles, camera, glm::vec3(0.0f, 0.0f, -8.0f)), 1);
  EXPECT_EQ(count(triangles, camera, glm::vec3(1.9f, -1.9f, -8.0f)), 1);
  EXPECT_EQ(count(triangles, camera, glm::vec3(2.2f, 0.0f, -8.0f)), 0);
  EXPECT_EQ(count(triangles, camera, glm::vec3(-5.0f, 0.0f, -8.0f)), 0);  // through and out
  // Between the light and the block nothing is shadowed.
  EXPECT_EQ(count(triangles, camera, glm::vec3(0.0f, 0.0f, -3.0f)), 0);
  // From the far side too.
  EXPECT_EQ(count(triangles, glm::vec3(-6.0f, -2.0f, -9.0f), glm::vec3(0.3f, 0.2f, -6.0f)), 1);
}

TEST(DepthMapCliffs, ASteepSmoothSlopeIsNoCliffAndAPlateauOverItIs) {
  // A plane whose distance grows by 4% of itself per texel across the map.
  std::vector<float> depth(kSize * kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      depth[size_t(y) * kSize + size_t(x)] = window(3.0f + 0.12f * float(x));
  std::vector<glm::vec4> triangles;
  EXPECT_EQ(append_depth_map_cliffs(depth, kSize, light(), 0.002f, 100.0f, triangles), 0u);
  EXPECT_TRUE(triangles.empty());
  // A 2×2 plateau 1% nearer than the slope under it: its 8 sides, and the
  // slope's 2 steps between its capped texels (which would leave slits
  // between their caps).
  for (int y = 7; y < 9; ++y)
    for (int x = 7; x < 9; ++x)
      depth[size_t(y) * kSize + size_t(x)] = window(0.99f * (3.0f + 0.12f * float(x)));
  EXPECT_EQ(append_depth_map_cliffs(depth, kSize, light(), 0.002f, 100.0f, triangles), 10u);
  // 1% is under a threshold of 2%: no cliff then.
  triangles.clear();
  EXPECT_EQ(append_depth_map_cliffs(depth, kSize, light(), 0.02f, 100.0f, triangles), 0u);
}

}  // namespace
}  // namespace sb::techniques::shadow_volume
