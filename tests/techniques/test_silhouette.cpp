// The CPU silhouettes of shadow_volume (techniques/shadow_volume/): loops,
// volumes and the auto mode's pyramid, against geometry: the true sphere and
// its exact silhouette circle, and a watertightness count of the volumes.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <tuple>

#include "scenes/sphere_grid.h"
#include "scenes/topology.h"
#include "shadow_volume/near_plane_pyramid.h"
#include "shadow_volume/pn_triangle.h"
#include "shadow_volume/silhouette.h"
#include "shadow_volume/volume_mesh.h"

namespace sb::techniques::shadow_volume {

using core::Bounds;
using core::Camera;
using core::Mesh;

namespace {

constexpr float kRadius = 0.5f;
const glm::vec3 kCentre(0.0f, 1.2f, 0.0f);
const glm::vec3 kLight(3.5f, 10.0f, 2.5f);

Silhouette extract(const Mesh& mesh, const glm::vec3& light, SilhouetteMode mode,
                   float epsilon = 0.01f, float offset = 0.0f) {
  const SilhouetteMesh shape = make_silhouette_mesh(mesh, mesh_edges(mesh));
  SilhouetteSettings s;
  s.mode = mode;
  s.epsilon = epsilon;
  s.offset = offset;
  Silhouette out;
  extract_silhouette(shape, light, s, out);
  return out;
}

// Distance from p to the circle where the light's rays graze the sphere.
float distance_to_true_silhouette(const glm::vec3& p, const glm::vec3& light) {
  const glm::vec3 axis = light - kCentre;
  const float d = glm::length(axis);
  const glm::vec3 a = axis / d;
  const float along = kRadius * kRadius / d;  // circle's plane from the centre
  const float ring = kRadius * std::sqrt(1.0f - along * along / (kRadius * kRadius));
  const glm::vec3 q = p - kCentre;
  const float h = glm::dot(q, a) - along;
  const float r = glm::length(q - glm::dot(q, a) * a);
  return std::sqrt(h * h + (r - ring) * (r - ring));
}

// Every directed triangle edge of a closed surface has its reverse as often.
size_t unmatched_edges(const std::vector<glm::vec4>& triangles) {
  using Key = std::tuple<float, float, float, float, float, float, float, float>;
  std::map<Key, int> count;
  for (size_t t = 0; t < triangles.size(); t += 3)
    for (size_t k = 0; k < 3; ++k) {
      const glm::vec4 a = triangles[t + k], b = triangles[t + (k + 1) % 3];
      if (a == b) continue;  // a degenerate triangle's collapsed edge
      count[{a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w}] += 1;
      count[{b.x, b.y, b.z, b.w, a.x, a.y, a.z, a.w}] -= 1;
    }
  size_t unmatched = 0;
  for (const auto& [key, n] : count) unmatched += size_t(std::abs(n));
  return unmatched / 2;
}

class EveryMode : public ::testing::TestWithParam<SilhouetteMode> {};

TEST_P(EveryMode, LoopsOnACoarseSphereAreClosedAndItsVolumeIsWatertight) {
  const Mesh sphere = make_uv_sphere("s", kCentre, kRadius, 8, 6);
  const Silhouette s = extract(sphere, kLight, GetParam());
  EXPECT_EQ(s.open_loops, 0u);
  ASSERT_EQ(s.loops.size(), 1u) << "a convex body has one silhouette loop";
  EXPECT_GE(s.loops[0].size(), 3u);
  VolumeVertices v;
  const auto range = append_volume(s, kLight, true, v);
  EXPECT_EQ(range.first, 0);
  EXPECT_EQ(size_t(range.sides + range.caps), v.vertices.size());
  EXPECT_EQ(unmatched_edges(v.vertices), 0u);
}

TEST_P(EveryMode, ALoopEdgeJoinsPointsOfTheSameTriangleOrEdge) {
  // Consecutive loop vertices are never far apart: no jump across the mesh.
  const Mesh sphere = make_uv_sphere("s", kCentre, kRadius, 8, 6);
  const Silhouette s = extract(sphere, kLight, GetParam());
  const float longest_mesh_edge = 2.0f * kRadius * std::sin(3.14159265f / 8.0f) * 1.01f;
  for (const auto& loop : s.loops)
    for (size_t i = 0; i < loop.size(); ++i)
      EXPECT_LE(glm::length(loop[i].mesh - loop[(i + 1) % loop.size()].mesh), longest_mesh_edge);
}

std::string mode_name(const ::testing::TestParamInfo<SilhouetteMode>& mode) {
  return mode.param == SilhouetteMode::Discrete   ? "discrete"
         : mode.param == SilhouetteMode::Accurate ? "accurate"
                                                  : "smooth";
}

INSTANTIATE_TEST_SUITE_P(Silhouette, EveryMode,
                         ::testing::Values(SilhouetteMode::Discrete, SilhouetteMode::Accurate,
                                           SilhouetteMode::Smooth),
                         mode_name);

float worst_distance(const Silhouette& s, bool smooth) {
  float worst = 0.0f;
  for (const auto& loop : s.loops)
    for (const auto& v : loop)
      worst = std::max(worst, distance_to_true_silhouette(smooth ? v.smooth : v.mesh, kLight));
  return worst;
}

TEST(Silhouette, SmoothVerticesLieWithinEpsilonOfTheTrueSilhouette) {
  const float epsilon = 0.01f;
  for (const auto& [slices, stacks] : {std::pair{8, 6}, {12, 8}, {20, 20}}) {
    const Mesh sphere = make_uv_sphere("s", kCentre, kRadius, slices, stacks);
    const Silhouette s = extract(sphere, kLight, SilhouetteMode::Smooth, epsilon);
    EXPECT_LT(worst_distance(s, true), epsilon) << slices << "x" << stacks;
  }
}

TEST(Silhouette, DiscreteAndAccurateVerticesOfACoarseSphereDoNot) {
  const Mesh sphere = make_uv_sphere("s", kCentre, kRadius, 8, 6);
  EXPECT_GT(worst_distance(extract(sphere, kLight, SilhouetteMode::Discrete), false), 0.01f);
  EXPECT_GT(worst_distance(extract(sphere, kLight, SilhouetteMode::Accurate), false), 0.01f);
}

TEST(Silhouette, SmoothSubdividesUntilTheCurveIsWithinEpsilonOfItsChords) {
  const Mesh sphere = make_uv_sphere("s", kCentre, kRadius, 8, 6);
  const size_t coarse = extract(sphere, kLight, SilhouetteMode::Smooth, 0.05f).loops[0].size();
  const size_t fine = extract(sphere, kLight, SilhouetteMode::Smooth, 0.0005f).loops[0].size();
  EXPECT_GT(fine, coarse);
}

TEST(Silhouette, TheSmoothOffsetMovesTheSilhouetteInwards) {
  const Mesh sphere = make_uv_sphere("s", kCentre, kRadius, 20, 20);
  const Silhouette s = extract(sphere, kLight, SilhouetteMode::Smooth, 0.01f, 0.02f);
  for (const auto& v : s.loops[0])
    EXPECT_NEAR(glm::length(v.smooth - kCentre), kRadius - 0.02f, 0.004f);
}

TEST(Silhouette, ACreaseGetsTwoSilhouetteVerticesAndStaysClosed) {
  // A cube with a normal per face: every vertex is split three ways, so the
  // smooth silhouette reaches each crease from both sides.
  Mesh cube;
  const glm::vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int a = 0; a < 3; ++a)
    for (float sign : {1.0f, -1.0f}) {
      const glm::vec3 n = sign * axes[a];
      const glm::vec3 u = sign * axes[(a + 1) % 3], w = axes[(a + 2) % 3];
      const uint32_t base = uint32_t(cube.positions.size());
      for (const glm::vec2 c :
           {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
        cube.positions.push_back(n + c.x * u + c.y * w);
        // Bent towards the corner, as a smoothing tool would: not the face's normal.
        cube.normals.push_back(glm::normalize(n + 0.5f * (c.x * u + c.y * w)));
      }
      cube.indices.insert(cube.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
  ASSERT_TRUE(analyse_topology(cube).closed());
  const glm::vec3 light(4.0f, 9.0f, 2.0f);
  for (SilhouetteMode mode :
       {SilhouetteMode::Discrete, SilhouetteMode::Accurate, SilhouetteMode::Smooth}) {
    const Silhouette s = extract(cube, light, mode);
    EXPECT_EQ(s.open_loops, 0u);
    VolumeVertices v;
    append_volume(s, light, true, v);
    EXPECT_EQ(unmatched_edges(v.vertices), 0u);
    if (mode != SilhouetteMode::Smooth) continue;
    size_t doubled = 0;  // consecutive vertices at one mesh point, two smooth points
    for (const auto& loop : s.loops)
      for (size_t i = 0; i < loop.size(); ++i) {
        const auto& a = loop[i];
        const auto& b = loop[(i + 1) % loop.size()];
        if (a.mesh == b.mesh && a.smooth != b.smooth) ++doubled;
      }
    EXPECT_GT(doubled, 0u);
  }
}

TEST(Silhouette, NormalsPerpendicularToTheLightAtBothEndsOfAnEdgeDoNotDivideByZero) {
  // An octahedron whose +x and +y corners have n·(l − v) = 0 exactly for the
  // light at (0, 1, 5), and within rounding of 0 for lights nearby.
  Mesh octa;
  octa.positions = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  octa.normals = {
      glm::normalize(glm::vec3(1, 1, 0)), {1, 0, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  octa.indices = {0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4, 1, 0, 5, 2, 1, 5, 3, 2, 5, 0, 3, 5};
  ASSERT_TRUE(analyse_topology(octa).closed());
  const glm::vec3 degenerate(0.0f, 1.0f, 5.0f);
  for (float delta : {0.0f, 1e-30f, -1e-30f, 1e-7f, -1e-7f})
    for (SilhouetteMode mode : {SilhouetteMode::Accurate, SilhouetteMode::Smooth}) {
      const glm::vec3 light = degenerate + glm::vec3(delta, delta, 0.0f);
      const Silhouette s = extract(octa, light, mode);
      EXPECT_EQ(s.open_loops, 0u) << delta;
      VolumeVertices v;
      append_volume(s, light, true, v);
      for (const glm::vec4& p : v.vertices)
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << delta;
      EXPECT_EQ(unmatched_edges(v.vertices), 0u) << delta;
    }
}

TEST(Silhouette, DiscreteLoopsFollowTheEdgesBetweenLitAndUnlitFaces) {
  // On a discrete loop every vertex is a mesh vertex.
  const Mesh sphere = make_uv_sphere("s", kCentre, kRadius, 8, 6);
  const Silhouette s = extract(sphere, kLight, SilhouetteMode::Discrete);
  for (const auto& v : s.loops[0]) {
    bool is_vertex = false;
    for (const glm::vec3& p : sphere.positions) is_vertex = is_vertex || p == v.mesh;
    EXPECT_TRUE(is_vertex);
  }
}

TEST(PnTriangle, InterpolatesItsCornersAndBulgesTowardsTheSphere) {
  const std::array<glm::vec3, 3> p{glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)};
  const PnTriangle pn(p, p);  // a unit sphere's octant: normals = positions
  EXPECT_EQ(pn.point({1, 0, 0}), p[0]);
  EXPECT_EQ(pn.point({0, 0, 1}), p[2]);
  const float flat = glm::length(glm::vec3(1.0f / 3.0f));
  const float curved = glm::length(pn.point(glm::vec3(1.0f / 3.0f)));
  EXPECT_GT(curved, flat + 0.15f);  // the flat centre is at 0.577
  // On an edge: the cubic Bézier p0, p0 + t0/3, p1 − t1/3, p1, with t0 and t1
  // the edge projected into the corners' tangent planes; at its middle
  // (p0 + 3·b1 + 3·b2 + p1) / 8.
  const glm::vec3 e = p[1] - p[0];
  const glm::vec3 b1 = p[0] + (e - glm::dot(e, p[0]) * p[0]) / 3.0f;
  const glm::vec3 b2 = p[1] - (e - glm::dot(e, p[1]) * p[1]) / 3.0f;
  const glm::vec3 middle = (p[0] + 3.0f * b1 + 3.0f * b2 + p[1]) / 8.0f;
  EXPECT_LT(glm::length(pn.point({0.5f, 0.5f, 0.0f}) - middle), 1e-6f);
}

TEST(NearPlanePyramid, FindsCastersBetweenTheLightAndTheNearPlaneOnly) {
  Camera camera;
  camera.eye = {0, 1, 5};
  camera.target = {0, 1, 0};
  camera.near_plane = 0.1f;
  const glm::mat4 vp = camera.projection(1.0f) * camera.view();
  const NearPlanePyramid pyramid({0, 10, 5}, vp);  // straight above the eye
  const auto box = [](glm::vec3 c, float h) {
    Bounds b;
    b.extend(c - h);
    b.extend(c + h);
    return b;
  };
  EXPECT_TRUE(pyramid.may_intersect(box({0, 5, 5}, 0.2f)));    // between light and eye
  EXPECT_FALSE(pyramid.may_intersect(box({0, 1, 0}, 0.5f)));   // in front of the camera
  EXPECT_FALSE(pyramid.may_intersect(box({3, 5, 5}, 0.2f)));   // beside the pyramid
  EXPECT_FALSE(pyramid.may_intersect(box({0, 12, 5}, 0.5f)));  // beyond the light
}

}  // namespace
}  // namespace sb::techniques::shadow_volume
