// Repeated casters (issue 65's glTF of one mesh placed 200,000 times at one
// spot) are traced once: the union of the casters, all V depends on, is the
// same, so the reference of a scene with repeats must be the reference of
// the scene without them, bit for bit, sampled or exact.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "reference/distinct_casters.h"
#include "reference/reference.h"
#include "test_scenes.h"

namespace {

using sb::core::Mesh;
using sb::core::Scene;
namespace ref = sb::reference;
using ref::detail::without_repeated_casters;

Scene with_copies(const Scene& base, size_t caster, int copies) {
  Scene s = base;
  for (int i = 0; i < copies; ++i) s.meshes.push_back(base.meshes[caster]);
  return s;
}

TEST(ReferenceDistinctCasters, KeepsOneOfEachRepeatedCasterAndEveryReceiver) {
  Scene s = with_copies(sbtest::sphere_over_plane(), 1, 500);
  s.meshes.push_back(s.meshes[0]);  // a second ground: a receiver, kept
  const auto distinct = without_repeated_casters(s);
  ASSERT_TRUE(distinct.has_value());
  ASSERT_EQ(distinct->meshes.size(), 3u);
  EXPECT_FALSE(distinct->meshes[0].casts_shadow);
  EXPECT_TRUE(distinct->meshes[1].casts_shadow);
  EXPECT_FALSE(distinct->meshes[2].casts_shadow);
  EXPECT_EQ(distinct->meshes[1].positions, s.meshes[1].positions);
}

TEST(ReferenceDistinctCasters, KeepsCastersThatDifferInAnyByte) {
  Scene s = with_copies(sbtest::sphere_over_plane(), 1, 3);
  s.meshes[2].positions[5].x = std::nextafter(s.meshes[2].positions[5].x, 10.0f);  // one ulp
  s.meshes[3].double_sided = true;  // never closed, in the exact reference
  std::swap(s.meshes[4].indices[0], s.meshes[4].indices[1]);  // wound the other way
  EXPECT_FALSE(without_repeated_casters(s).has_value());
  EXPECT_FALSE(without_repeated_casters(sbtest::sphere_over_plane()).has_value());
}

TEST(ReferenceDistinctCasters, RepeatsChangeNoPixelOfTheReference) {
  const Scene once = sbtest::sphere_over_plane();
  const Scene many = with_copies(once, 1, 200);
  const ref::GBuffer g = ref::trace_gbuffer(once, 64, 48);
  for (const bool exact : {false, true}) {
    ref::Settings s(16, 7);
    s.exact = exact;
    const ref::Result a = ref::compute(once, g.positions, g.normals, s);
    const ref::Result b = ref::compute(many, g.positions, g.normals, s);
    EXPECT_EQ(a.visibility.data, b.visibility.data) << (exact ? "exact" : "sampled");
    EXPECT_EQ(a.penumbra, b.penumbra) << (exact ? "exact" : "sampled");
    // And there is a shadow to keep: some pixels dark, some soft.
    int dark = 0, soft = 0;
    for (float v : a.visibility.data) {
      dark += v == 0.0f;
      soft += v > 0.0f && v < 1.0f;
    }
    EXPECT_GT(dark, 0);
    EXPECT_GT(soft, 0);
  }
}

}  // namespace
