// The penumbra wedges' CPU geometry (techniques/penumbra_wedge/): each
// wedge's hull against the set it must bound, sampled from its definition
// (points y on a ray from a light point through a point of the edge), its
// watertightness and winding, Lengyel's half-wedge planes, and the edge cases
// that must neither divide by zero nor emit a broken hull.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <tuple>
#include <utility>

#include "penumbra_wedge/wedge_geometry.h"

namespace sb::techniques::penumbra_wedge {

using core::AreaLight;
using core::Bounds;

namespace {

AreaLight square_light(float size, const glm::vec3& centre = {0.0f, 10.0f, 0.0f}) {
  AreaLight l;
  l.center = centre;
  l.half_u = {0.5f * size, 0.0f, 0.0f};
  l.half_v = {0.0f, 0.0f, 0.5f * size};
  l.target = centre - glm::vec3(0.0f, 1.0f, 0.0f);
  return l;
}

// The scene of these tests: a ground at y = 0 under the light at y = 10.
WedgeRange scene_range(const LightFrame& frame) {
  Bounds scene;
  scene.lo = {-40.0f, 0.0f, -40.0f};
  scene.hi = {40.0f, 8.0f, 40.0f};
  return wedge_range(frame, scene);
}

struct Face {
  glm::vec3 normal;  // outwards, unit
  glm::vec3 point;
};

std::vector<Face> faces(const WedgeBatch& batch) {
  std::vector<Face> out;
  for (size_t t = 0; t < batch.indices.size(); t += 3) {
    const glm::vec3 p0 = batch.vertices[batch.indices[t]].position;
    const glm::vec3 p1 = batch.vertices[batch.indices[t + 1]].position;
    const glm::vec3 p2 = batch.vertices[batch.indices[t + 2]].position;
    out.push_back({glm::normalize(glm::cross(p1 - p0, p2 - p0)), p0});
  }
  return out;
}

float outside_by(const std::vector<Face>& fs, const glm::vec3& y) {
  float worst = -1e30f;
  for (const Face& f : fs) worst = std::max(worst, glm::dot(f.normal, y - f.point));
  return worst;
}

bool half_wedge_accepts(const WedgeRecord& w, const glm::vec3& y,
                        const glm::vec3& light = {0.0f, 10.0f, 0.0f}) {
  const glm::vec4 p(y, 1.0f);
  const float bound =
      glm::dot(w.centre_plane, p) < 0.0f ? glm::dot(w.first_bound, p) : glm::dot(w.second_bound, p);
  return bound >= -kHalfWedgeTolerance * glm::length(y - light);
}

// Directed edges (by position) that lack their reverse.
size_t unmatched_edges(const WedgeBatch& batch) {
  using Key = std::tuple<float, float, float, float, float, float>;
  std::map<Key, int> count;
  for (size_t t = 0; t < batch.indices.size(); t += 3)
    for (size_t k = 0; k < 3; ++k) {
      const glm::vec3 a = batch.vertices[batch.indices[t + k]].position;
      const glm::vec3 b = batch.vertices[batch.indices[t + (k + 1) % 3]].position;
      count[{a.x, a.y, a.z, b.x, b.y, b.z}] += 1;
      count[{b.x, b.y, b.z, a.x, a.y, a.z}] -= 1;
    }
  size_t unmatched = 0;
  for (const auto& [edge, c] : count) unmatched += c != 0;
  return unmatched;
}

// Random edges under lights of several sizes: every point of the wedge's
// defining set within the scene's range is inside the hull and passes the
// half-wedge test.
TEST(WedgeGeometry, TheHullAndTheHalfWedgeTestContainEveryPointTheEdgeCanShadow) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  size_t samples = 0;
  float worst = -1e30f;
  size_t rejected = 0;
  for (const float size : {0.01f, 1.0f, 4.0f}) {
    const AreaLight light = square_light(size);
    const LightFrame frame(light);
    const WedgeRange range = scene_range(frame);
    for (int e = 0; e < 200; ++e) {
      const glm::vec3 a(4.0f * unit(rng) - 2.0f, 0.5f + 6.0f * unit(rng), 4.0f * unit(rng) - 2.0f);
      const glm::vec3 b =
          a + glm::vec3(2.0f * unit(rng) - 1.0f, 1.0f * unit(rng) - 0.5f, 2.0f * unit(rng) - 1.0f);
      WedgeBatch batch;
      ASSERT_TRUE(append_wedge(frame, a, b, range, batch));
      ASSERT_EQ(batch.wedges.size(), 1u);
      EXPECT_EQ(unmatched_edges(batch), 0u);
      for (const WedgeVertex& v : batch.vertices)  // cut to the scene's box
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(v.position, range.box.lo)) &&
                    glm::all(glm::lessThanEqual(v.position, range.box.hi)));
      const std::vector<Face> fs = faces(batch);
      for (int s = 0; s < 200; ++s) {
        const glm::vec3 x = a + unit(rng) * (b - a);
        const glm::vec3 l = light.point(unit(rng), unit(rng));
        // Up to the ground (light-frame z = 10), the scene's far end.
        const float t = unit(rng) * x.y / (l.y - x.y);
        const glm::vec3 y = x + t * (x - l);
        ++samples;
        worst = std::max(worst, outside_by(fs, y) / (1.0f + glm::length(y)));
        rejected += !half_wedge_accepts(batch.wedges[0], y);
      }
    }
  }
  std::printf("%zu points: furthest outside the hull %.3g (relative), rejected %zu\n", samples,
              double(worst), rejected);
  EXPECT_GT(samples, 100000u);
  EXPECT_LT(worst, 1e-5f);
  EXPECT_EQ(rejected, 0u);
}

// Outward winding: every hull vertex lies on or behind every face.
TEST(WedgeGeometry, FacesAreWoundOutwards) {
  const LightFrame frame(square_light(2.0f));
  WedgeBatch batch;
  ASSERT_TRUE(
      append_wedge(frame, {-0.7f, 3.0f, 0.2f}, {0.5f, 3.4f, -0.3f}, scene_range(frame), batch));
  const std::vector<Face> fs = faces(batch);
  ASSERT_GE(fs.size(), 4u);
  for (const Face& f : fs)
    for (const WedgeVertex& v : batch.vertices)
      EXPECT_LE(glm::dot(f.normal, v.position - f.point), 1e-4f);
}

// The half-wedge test rejects points between the light and the edge, and
// points beside the wedge.
TEST(WedgeGeometry, TheHalfWedgeTestRejectsPointsTheEdgeCannotShadow) {
  const LightFrame frame(square_light(1.0f));
  WedgeBatch batch;
  // An edge along x at height 5, beside the light's axis.
  ASSERT_TRUE(
      append_wedge(frame, {-1.0f, 5.0f, 1.0f}, {1.0f, 5.0f, 1.0f}, scene_range(frame), batch));
  const WedgeRecord& w = batch.wedges[0];
  EXPECT_TRUE(half_wedge_accepts(w, {0.0f, 0.0f, 2.0f}));    // under it, along the centre's ray
  EXPECT_FALSE(half_wedge_accepts(w, {0.0f, 7.5f, 1.0f}));   // above it, towards the light
  EXPECT_FALSE(half_wedge_accepts(w, {0.0f, 0.0f, -3.0f}));  // far to the light's side
  EXPECT_FALSE(half_wedge_accepts(w, {0.0f, 0.0f, 6.0f}));   // far outside
}

// Edges the shader must survive: their wedges are finite, closed, or absent.
TEST(WedgeGeometry, DegenerateAndCrossingEdgesGiveFiniteClosedHullsOrNone) {
  const LightFrame frame(square_light(1.0f));
  const WedgeRange range = scene_range(frame);
  const auto finite = [](const WedgeBatch& b) {
    for (const WedgeVertex& v : b.vertices)
      if (!std::isfinite(v.position.x) || !std::isfinite(v.position.y) ||
          !std::isfinite(v.position.z))
        return false;
    for (const WedgeRecord& w : b.wedges)
      for (const glm::vec4& q : {w.a, w.b, w.centre_plane, w.first_bound, w.second_bound})
        if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z) ||
            !std::isfinite(q.w))
          return false;
    return true;
  };
  {  // a zero-length edge: nothing
    WedgeBatch b;
    EXPECT_FALSE(append_wedge(frame, {0.3f, 4.0f, 0.1f}, {0.3f, 4.0f, 0.1f}, range, b));
    EXPECT_TRUE(b.vertices.empty());
  }
  {  // wholly behind the light's plane: nothing
    WedgeBatch b;
    EXPECT_FALSE(append_wedge(frame, {0.0f, 11.0f, 0.0f}, {1.0f, 12.0f, 0.0f}, range, b));
  }
  {  // crossing the light's plane: cut at the near distance
    WedgeBatch b;
    ASSERT_TRUE(append_wedge(frame, {2.0f, 12.0f, 0.0f}, {2.0f, 6.0f, 0.0f}, range, b));
    EXPECT_TRUE(finite(b));
    EXPECT_EQ(unmatched_edges(b), 0u);
    EXPECT_GE(b.wedges[0].a.z, range.near * 0.999f);
  }
  {  // parallel to a light border, directly under it
    WedgeBatch b;
    ASSERT_TRUE(append_wedge(frame, {-1.0f, 5.0f, 0.5f}, {1.0f, 5.0f, 0.5f}, range, b));
    EXPECT_TRUE(finite(b));
    EXPECT_EQ(unmatched_edges(b), 0u);
  }
  {  // pointing at the light's centre: no two planes bound it, no rejection
    WedgeBatch b;
    ASSERT_TRUE(append_wedge(frame, {0.0f, 4.0f, 0.0f}, {0.0f, 6.0f, 0.0f}, range, b));
    EXPECT_TRUE(finite(b));
    EXPECT_EQ(unmatched_edges(b), 0u);
    EXPECT_EQ(b.wedges[0].first_bound, glm::vec4(0.0f));
    EXPECT_TRUE(half_wedge_accepts(b.wedges[0], {5.0f, 0.0f, 5.0f}));
  }
}

// A light of no area (light_size 0) still gets an orthonormal frame, facing
// its target, and says it has no area (so no wedges are built for it).
TEST(WedgeGeometry, APointLightHasAFiniteFrameAndNoArea) {
  AreaLight point = square_light(0.0f);
  const LightFrame frame(point);
  EXPECT_FALSE(frame.has_area());
  EXPECT_TRUE(LightFrame(square_light(1.0f)).has_area());
  for (const glm::vec3& axis : {frame.u, frame.v, frame.n}) {
    EXPECT_TRUE(std::isfinite(axis.x) && std::isfinite(axis.y) && std::isfinite(axis.z));
    EXPECT_NEAR(glm::length(axis), 1.0f, 1e-6f);
  }
  EXPECT_NEAR(glm::dot(frame.u, frame.v), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(frame.n, glm::vec3(0.0f, -1.0f, 0.0f)), 1.0f, 1e-6f);  // towards the target
}

}  // namespace
}  // namespace sb::techniques::penumbra_wedge
