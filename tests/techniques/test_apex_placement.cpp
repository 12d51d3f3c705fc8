// two_map_bound's apexes (techniques/two_map/apex_placement.h) against the
// crossings of Shypula 2008's figures 8.4–8.5, computed here from the lines
// themselves, and the shadows they cast against the true penumbra and
// umbra of an occluder as wide as the extent.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "two_map/apex_placement.h"

namespace sb::techniques::two_map {

using core::AreaLight;
using core::Bounds;
using core::JobError;

namespace {

// A light facing down (−y) from (0, 10, 0): its frame's z is the depth
// below it.
AreaLight light_of_size(float w, float h) {
  AreaLight l;
  l.center = {0.0f, 10.0f, 0.0f};
  l.target = {0.0f, 0.0f, 0.0f};
  l.half_u = {0.5f * w, 0.0f, 0.0f};
  l.half_v = {0.0f, 0.0f, 0.5f * h};
  return l;
}

Bounds box(glm::vec3 lo, glm::vec3 hi) {
  Bounds b;
  b.extend(lo);
  b.extend(hi);
  return b;
}

// Where the lines (a0 → b0) and (a1 → b1) in the (x, z) plane cross: z.
double crossing_depth(double a0, double b0, double a1, double b1, double depth) {
  // x = a + (b − a)·z/D on each line.
  return depth * (a1 - a0) / ((b0 - a0) - (b1 - a1));
}

TEST(ApexPlacement, ApexesAreWhereTheLightsEdgesLinesToTheCastersEdgesCross) {
  const LightFrame frame(light_of_size(1.0f, 1.0f));
  // Casters 4 below the light (y = 6), x ∈ [1, 4], z ∈ [−1.5, 1.5].
  const Bounds casters = box({1.0f, 5.0f, -1.5f}, {4.0f, 6.0f, 1.5f});
  const TwoApexes a = place_apexes(frame, casters);
  EXPECT_FLOAT_EQ(a.caster_depth, 4.0f);
  // The light frame's x may be ±world x; use |local| consistently.
  const glm::vec3 lo = frame.to_light({1.0f, 6.0f, 0.0f}), hi = frame.to_light({4.0f, 6.0f, 0.0f});
  const double x_lo = std::min(lo.x, hi.x), x_hi = std::max(lo.x, hi.x);
  // Penumbra: light edge −½ to the extent's far edge, +½ to its near edge.
  const double zp = crossing_depth(-0.5, x_hi, 0.5, x_lo, 4.0);
  // Umbra: light edge −½ to the near edge, +½ to the far edge (behind the light).
  const double zu = crossing_depth(-0.5, x_lo, 0.5, x_hi, 4.0);
  // Both axes have c = 1.5 > l = 0.5: the same crossing depths.
  EXPECT_NEAR(a.penumbra_depth, zp, 1e-5);
  EXPECT_NEAR(zp, 4.0 * 0.5 / 2.0, 1e-9);
  ASSERT_TRUE(a.has_umbra_apex);
  EXPECT_NEAR(a.umbra_depth, zu, 1e-5);
  EXPECT_NEAR(zu, -4.0 * 0.5 / 1.0, 1e-9);
  // Each apex lies on its crossing lines: x = −½ + (x_hi + ½)·z/D.
  const glm::vec3 p = frame.to_light(a.penumbra_apex), u = frame.to_light(a.umbra_apex);
  EXPECT_NEAR(p.x, -0.5 + (x_hi + 0.5) * zp / 4.0, 1e-5);
  EXPECT_NEAR(u.x, -0.5 + (x_lo + 0.5) * zu / 4.0, 1e-5);
  EXPECT_NEAR(p.z, zp, 1e-5);
  EXPECT_NEAR(u.z, zu, 1e-5);
}

// From the apexes, the shadow of the extent's edge on a receiver at depth Z
// falls exactly on the true outer and inner penumbra boundaries of an
// occluder as wide as the extent.
TEST(ApexPlacement, TheirShadowsOfTheExtentsEdgesAreThePenumbrasBoundaries) {
  const LightFrame frame(light_of_size(2.0f, 2.0f));
  const Bounds casters = box({-3.0f, 5.999f, -3.0f}, {3.0f, 6.0f, 3.0f});  // c = 3, l = 1, D = 4
  const TwoApexes a = place_apexes(frame, casters);
  ASSERT_TRUE(a.has_umbra_apex);
  const double depth = 4.0, l = 1.0, c = 3.0, receiver = 10.0;
  const auto shadow_x = [&](glm::vec3 apex_local, double edge_x) {
    return apex_local.x +
           (edge_x - apex_local.x) * (receiver - apex_local.z) / (depth - apex_local.z);
  };
  const glm::vec3 p = frame.to_light(a.penumbra_apex), u = frame.to_light(a.umbra_apex);
  // Outer boundary of the edge at +c: from the light's −l side.
  EXPECT_NEAR(shadow_x(p, c), -l + (c + l) * receiver / depth, 1e-4);
  // Inner boundary: from the light's +l side.
  EXPECT_NEAR(shadow_x(u, c), l + (c - l) * receiver / depth, 1e-4);
}

TEST(ApexPlacement, ALightAtLeastAsWideAsTheCastersHasNoUmbraApex) {
  const Bounds casters = box({-0.5f, 5.0f, -0.5f}, {0.5f, 6.0f, 0.5f});  // c = 0.5
  for (const float side : {1.0f, 3.0f, 100.0f}) {
    SCOPED_TRACE(side);
    const TwoApexes a = place_apexes(LightFrame(light_of_size(side, side)), casters);
    EXPECT_FALSE(a.has_umbra_apex);
    EXPECT_TRUE(std::isfinite(a.penumbra_depth));
    EXPECT_GT(a.penumbra_depth, 0.0f);
    EXPECT_LT(a.penumbra_depth, a.caster_depth);
  }
  // Wider on one axis only: still none (the extent bounds no umbra there).
  const TwoApexes a = place_apexes(LightFrame(light_of_size(0.2f, 3.0f)), casters);
  EXPECT_FALSE(a.has_umbra_apex);
}

TEST(ApexPlacement, APointLightPutsBothApexesAtItsCentre) {
  const Bounds casters = box({-1.0f, 5.0f, -1.0f}, {1.0f, 6.0f, 1.0f});
  const TwoApexes a = place_apexes(LightFrame(light_of_size(0.0f, 0.0f)), casters);
  EXPECT_EQ(a.penumbra_depth, 0.0f);
  ASSERT_TRUE(a.has_umbra_apex);
  EXPECT_EQ(a.umbra_depth, 0.0f);
  EXPECT_LT(glm::length(a.penumbra_apex - glm::vec3(0.0f, 10.0f, 0.0f)), 1e-6f);
  EXPECT_LT(glm::length(a.umbra_apex - glm::vec3(0.0f, 10.0f, 0.0f)), 1e-6f);
}

TEST(ApexPlacement, AnUmbraApexFarBehindTheLightStopsAtTheLimit) {
  // c − l tiny: the crossing is 4·0.5/0.001 = 2000 behind the light.
  const Bounds casters = box({-0.501f, 5.0f, -0.501f}, {0.501f, 6.0f, 0.501f});
  const TwoApexes a = place_apexes(LightFrame(light_of_size(1.0f, 1.0f)), casters);
  ASSERT_TRUE(a.has_umbra_apex);
  EXPECT_FLOAT_EQ(a.umbra_depth, -kFarthestUmbraApex * a.caster_depth);
}

TEST(ApexPlacement, CastersReachingTheLightsPlaneAreAJobError) {
  const Bounds casters = box({-1.0f, 5.0f, -1.0f}, {1.0f, 10.5f, 1.0f});
  EXPECT_THROW(place_apexes(LightFrame(light_of_size(1.0f, 1.0f)), casters), JobError);
}

}  // namespace
}  // namespace sb::techniques::two_map
