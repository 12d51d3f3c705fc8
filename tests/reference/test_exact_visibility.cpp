// The exact reference's visibility (harness/reference/exact_visibility.h),
// no GL: a plate parallel to the light against the closed form, the
// horizon alone against the light's part above an axis-aligned tangent
// plane, random triangles against a dense stratified ray count, closed-caster
// culling against keeping every triangle, and the scenes it cannot do.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "reference/exact_visibility.h"
#include "test_scenes.h"

namespace {

using sb::reference::ExactVisibility;

// An axis-aligned box, outward counter-clockwise faces.
sb::core::Mesh box(const std::string& name, glm::vec3 lo, glm::vec3 hi) {
  sb::core::Mesh m;
  m.name = name;
  for (int i = 0; i < 8; ++i)
    m.positions.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  m.indices = {0, 2, 3, 0, 3, 1,   // -z
               4, 5, 7, 4, 7, 6,   // +z
               0, 1, 5, 0, 5, 4,   // -y
               2, 6, 7, 2, 7, 3,   // +y
               0, 4, 6, 0, 6, 2,   // -x
               1, 3, 7, 1, 7, 5};  // +x
  return m;
}

double signed_volume(const sb::core::Mesh& m) {
  double v = 0.0;
  for (size_t i = 0; i < m.indices.size(); i += 3)
    v += glm::dot(glm::dvec3(m.positions[m.indices[i]]),
                  glm::cross(glm::dvec3(m.positions[m.indices[i + 1]]),
                             glm::dvec3(m.positions[m.indices[i + 2]])));
  return v / 6.0;
}

// The light of test_scenes.h: 2×2 at y = 10, facing down.
sb::core::Scene plate_scene(bool with_ground) {
  sb::core::Scene s;
  s.light = sbtest::square_light();
  s.light.target = {0, 0, 0};
  // One open quad: a closed box's sides and bottom would widen its shadow
  // beyond the top face's closed form.
  s.meshes.push_back(sbtest::quad("plate", {-0.7f, 4.0f, -1.3f}, {1.1f, 4.0f, -1.3f},
                                  {1.1f, 4.0f, 0.4f}, {-0.7f, 4.0f, 0.4f}, true));
  if (with_ground)
    s.meshes.push_back(
        sbtest::quad("ground", {-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}, false));
  return s;
}

// The plate projected from the point (x, y, z) below it onto the light's
// plane is the rectangle scaled by (H − y) / (h − y) about the point.
double plate_visibility(double x, double y, double z) {
  const double k = (10.0 - y) / (4.0 - y), half = 1.0;
  const auto overlap = [&](double lo, double hi, double at) {
    const double a = at + (lo - at) * k, b = at + (hi - at) * k;
    return std::max(0.0, std::min(b, half) - std::max(a, -half));
  };
  return 1.0 - overlap(-0.7, 1.1, x) * overlap(-1.3, 0.4, z) / 4.0;
}

TEST(ReferenceExact, APlateParallelToTheLightMatchesTheClosedForm) {
  const sb::core::Scene scene = plate_scene(true);
  {
    const ExactVisibility exact(scene);
    EXPECT_EQ(exact.unsupported(), "");
    double worst = 0.0;
    int penumbra = 0;
    for (int i = 0; i <= 346; ++i)
      for (int j = 0; j <= 314; ++j) {
        const double x = -3.0 + 0.0173 * i, z = -3.0 + 0.0191 * j;
        // The reference looks from 2^-16 · max(|p|∞, M) above the surface,
        // as Monte Carlo's rays start: the ground is no caster, so M = 0.
        const double eps = 0x1p-16 * std::max(std::abs(x), std::abs(z));
        const double truth = plate_visibility(x, eps, z);
        worst = std::max(worst, std::abs(exact.visibility({x, 0.0, z}, {0, 1, 0}) - truth));
        penumbra += truth > 0.0 && truth < 1.0;
      }
    std::printf("%d penumbra points, max |V - closed form| %.2e\n", penumbra, worst);
    EXPECT_GT(penumbra, 10000);
    EXPECT_LT(worst, 1e-5);
  }
}

// No caster; the tangent plane's normal tilts about z, so the plane meets
// the light's plane in a line x = const, and V is the part of the light on
// its upper side.
TEST(ReferenceExact, TheHorizonAloneHidesTheLightBelowTheTangentPlane) {
  sb::core::Scene scene;
  scene.light = sbtest::square_light();
  scene.light.target = {0, 0, 0};
  const ExactVisibility exact(scene);
  for (const double tilt : {0.0, 0.05, 0.1, 0.2, -0.15, 0.5}) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(std::sin(tilt), std::cos(tilt), 0.0));
    const glm::dvec3 p(0.3, 2.0, -0.4);
    // n·(X − p) = 0 on y = 10: x = p.x − (10 − p.y)·n.y/n.x; above it where n·(X − p) > 0.
    double lit = 1.0;
    if (n.x != 0.0) {
      const double line = p.x - (10.0 - p.y) * n.y / n.x;
      const double above =
          n.x > 0.0 ? std::clamp(1.0 - line, 0.0, 2.0) : std::clamp(line + 1.0, 0.0, 2.0);
      lit = above / 2.0;
    }
    EXPECT_NEAR(exact.visibility(p, n), lit, 1e-7) << "tilt " << tilt;
  }
}

// Möller–Trumbore: does the segment from o to o + d (t in (0, 1)) cross the triangle?
bool crosses(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a, const glm::dvec3& b,
             const glm::dvec3& c) {
  const glm::dvec3 e1 = b - a, e2 = c - a, q = glm::cross(d, e2);
  const double det = glm::dot(e1, q);
  if (std::abs(det) < 1e-14) return false;
  const glm::dvec3 s = o - a;
  const double u = glm::dot(s, q) / det;
  if (u < 0.0 || u > 1.0) return false;
  const glm::dvec3 r = glm::cross(s, e1);
  const double v = glm::dot(d, r) / det;
  if (v < 0.0 || u + v > 1.0) return false;
  const double t = glm::dot(e2, r) / det;
  return t > 0.0 && t < 1.0;
}

// Random overlapping triangles between the light and points on the ground,
// against a count of rays to the centres of 400×400 cells of the light (a
// midpoint rule, whose error is a fraction of a cell row per edge that
// crosses the light: here it agreed to 3e-5).
TEST(ReferenceExact, RandomTrianglesAgreeWithADenseRayCount) {
  sb::core::Scene scene;
  scene.light = sbtest::square_light();
  scene.light.target = {0, 0, 0};
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> xz(-1.5f, 1.5f), y(3.0f, 8.0f), d(-0.8f, 0.8f);
  sb::core::Mesh m;
  m.name = "triangles";
  for (int i = 0; i < 12; ++i) {
    const glm::vec3 c(xz(rng), y(rng), xz(rng));
    for (int k = 0; k < 3; ++k) {
      m.indices.push_back(uint32_t(m.positions.size()));
      m.positions.push_back(c + glm::vec3(d(rng), 0.3f * d(rng), d(rng)));
    }
  }
  scene.meshes.push_back(m);
  const ExactVisibility exact(scene);
  std::uniform_real_distribution<double> ground(-1.5, 1.5);
  constexpr int kCells = 400;
  int soft = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const glm::dvec3 p(ground(rng), 0.0, ground(rng));
    int visible = 0;
    for (int i = 0; i < kCells; ++i)
      for (int j = 0; j < kCells; ++j) {
        const glm::dvec3 l(-1.0 + (i + 0.5) * 2.0 / kCells, 10.0, -1.0 + (j + 0.5) * 2.0 / kCells);
        bool hit = false;
        for (size_t t = 0; t < m.indices.size() && !hit; t += 3)
          hit = crosses(p, l - p, m.positions[m.indices[t]], m.positions[m.indices[t + 1]],
                        m.positions[m.indices[t + 2]]);
        visible += !hit;
      }
    const double counted = double(visible) / (kCells * kCells);
    const double v = exact.visibility(p, {0, 1, 0});
    soft += v > 0.01 && v < 0.99;
    std::printf("point %d: exact %.5f, counted %.5f\n", trial, v, counted);
    EXPECT_NEAR(v, counted, 5e-4) << "point " << trial;
  }
  EXPECT_GE(soft, 6) << "too few points see overlapping penumbrae";
}

// A closed box seen from points around it: culling the triangles that face
// away from the point changes nothing.
TEST(ReferenceExact, ClosedCastersKeepOnlyTheirNearSideWhicheverWayTheyWind) {
  sb::core::Scene scene;
  scene.light = sbtest::square_light();
  scene.light.target = {0, 0, 0};
  scene.meshes.push_back(box("box", {-0.5f, 3.0f, -0.3f}, {0.6f, 4.5f, 0.7f}));
  ASSERT_GT(signed_volume(scene.meshes[0]), 0.0) << "faces must wind outwards";
  sb::core::Scene inward = scene;  // the same box wound the other way
  for (size_t i = 0; i + 2 < inward.meshes[0].indices.size(); i += 3)
    std::swap(inward.meshes[0].indices[i + 1], inward.meshes[0].indices[i + 2]);
  const ExactVisibility all(scene, {false}), culled(scene, {true}), culled_inward(inward, {true});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> g(-2.0, 2.0);
  for (int i = 0; i < 400; ++i) {
    const glm::dvec3 p(g(rng), 0.0, g(rng));
    const double v = all.visibility(p, {0, 1, 0});
    EXPECT_NEAR(v, culled.visibility(p, {0, 1, 0}), 1e-7);
    EXPECT_NEAR(v, culled_inward.visibility(p, {0, 1, 0}), 1e-7);
  }
}

TEST(ReferenceExact, APointInsideAClosedCasterIsInItsUmbraAsEveryShadowRayIs) {
  // A silhouette pixel can land on a back face and take the viewer-facing
  // normal, which points into the mesh: every Monte Carlo shadow ray from
  // there hits the mesh from inside. Seen from inside, a closed caster has
  // no near side to keep; the segment to the light's centre leaves it, so
  // the exact reference covers the whole light too.
  sb::core::Scene scene;
  scene.light = sbtest::square_light();
  scene.light.target = {0, 0, 0};
  scene.meshes.push_back(box("box", {-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f}));
  const ExactVisibility exact(scene, {true});
  // On the top face, its normal flipped to point down into the box.
  EXPECT_EQ(exact.visibility({0.1, 1.0, 0.2}, {0, -1, 0}), 0.0);
  EXPECT_EQ(exact.visibility({0.1, 0.5, 0.2}, {0, 1, 0}), 0.0);  // well inside
  // On the top face, facing up: the whole light is above it.
  EXPECT_EQ(exact.visibility({0.1, 1.0, 0.2}, {0, 1, 0}), 1.0);
}

// The union drops the edges that two polygons run along in opposite
// directions before Clipper sees them: triangles tiling a ring (sharing
// edges, around a hole) cover the ring's area, and two overlapping squares
// their union's, by inclusion and exclusion.
TEST(ReferenceExact, TheUnionOfTrianglesTilingARingIsTheRingsArea) {
  const std::vector<glm::dvec2> outer{{-0.8, -0.8}, {0.8, -0.8}, {0.8, 0.8}, {-0.8, 0.8}};
  const std::vector<glm::dvec2> inner{{-0.3, -0.3}, {0.3, -0.3}, {0.3, 0.3}, {-0.3, 0.3}};
  std::vector<std::vector<glm::dvec2>> ring;
  for (size_t i = 0; i < 4; ++i) {
    const size_t j = (i + 1) % 4;
    ring.push_back({outer[i], outer[j], inner[j]});
    ring.push_back({outer[i], inner[j], inner[i]});
  }
  EXPECT_NEAR(ExactVisibility::union_area(ring, 1.0, 1.0), 1.6 * 1.6 - 0.6 * 0.6, 1e-8);
  // A triangle inside the ring changes nothing; one over the hole fills it.
  ring.push_back({{-0.7, -0.7}, {-0.4, -0.7}, {-0.4, -0.4}});
  EXPECT_NEAR(ExactVisibility::union_area(ring, 1.0, 1.0), 1.6 * 1.6 - 0.6 * 0.6, 1e-8);
  ring.push_back({{-0.3, -0.3}, {0.3, -0.3}, {0.3, 0.3}});
  ring.push_back({{-0.3, -0.3}, {0.3, 0.3}, {-0.3, 0.3}});
  EXPECT_NEAR(ExactVisibility::union_area(ring, 1.0, 1.0), 1.6 * 1.6, 1e-8);
  const std::vector<std::vector<glm::dvec2>> squares{
      {{-0.5, -0.5}, {0.3, -0.5}, {0.3, 0.3}, {-0.5, 0.3}},
      {{-0.3, -0.3}, {0.5, -0.3}, {0.5, 0.5}, {-0.3, 0.5}}};
  EXPECT_NEAR(ExactVisibility::union_area(squares, 1.0, 1.0), 0.64 + 0.64 - 0.36, 1e-8);
}

// image() walks the caster hierarchy once per tile of pixels and then only
// the leaves that tile kept: the same V, bit for bit, as each pixel's own
// walk, on tiles of one surface, tiles of scattered points (inside and
// around closed boxes, facing anywhere) and tiles with background.
TEST(ReferenceExact, TheImageIsEveryPixelsOwnVisibility) {
  sb::core::Scene scene;
  scene.light = sbtest::square_light();
  scene.light.target = {0, 0, 0};
  std::mt19937 rng(66);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<bool> closed;
  for (int i = 0; i < 4; ++i) {
    const glm::vec3 lo(4.0f * unit(rng) - 2.5f, 1.0f + 4.0f * unit(rng), 4.0f * unit(rng) - 2.5f);
    scene.meshes.push_back(box("box", lo, lo + glm::vec3(0.3f) + unit(rng) * glm::vec3(1.0f)));
    closed.push_back(true);
  }
  scene.meshes.push_back(sbtest::sphere({0.8f, 2.5f, -0.6f}, 0.7f, 12, 8));
  closed.push_back(false);
  sb::core::Mesh triangles;
  triangles.name = "triangles";
  for (int i = 0; i < 40; ++i) {
    const glm::vec3 c(6.0f * unit(rng) - 3.0f, 1.0f + 7.0f * unit(rng), 6.0f * unit(rng) - 3.0f);
    for (int k = 0; k < 3; ++k) {
      triangles.indices.push_back(uint32_t(triangles.positions.size()));
      triangles.positions.push_back(
          c + 0.6f * glm::vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f));
    }
  }
  scene.meshes.push_back(triangles);
  closed.push_back(false);
  const ExactVisibility exact(scene, closed);

  constexpr int kWidth = 44, kHeight = 36;
  sb::core::ImageF positions(kWidth, kHeight, 4, 0.0f), normals(kWidth, kHeight, 3, 0.0f);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const size_t i = size_t(y) * kWidth + size_t(x);
      glm::vec3 p, n(0.0f, 1.0f, 0.0f);
      if (y < 14) {  // the ground, smoothly
        p = {-3.0f + 6.0f * float(x) / kWidth, 0.0f, -3.0f + 6.0f * float(y) / 14.0f};
      } else if (y < 30) {  // anywhere, facing anywhere
        p = {6.0f * unit(rng) - 3.0f, 6.0f * unit(rng), 6.0f * unit(rng) - 3.0f};
        n = glm::vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f);
      } else {  // the ground, some of it background
        if (unit(rng) < 0.4f) continue;
        p = {6.0f * unit(rng) - 3.0f, 0.0f, 6.0f * unit(rng) - 3.0f};
      }
      positions.data[i * 4 + 0] = p.x;
      positions.data[i * 4 + 1] = p.y;
      positions.data[i * 4 + 2] = p.z;
      positions.data[i * 4 + 3] = 1.0f;
      normals.data[i * 3 + 0] = n.x;
      normals.data[i * 3 + 1] = n.y;
      normals.data[i * 3 + 2] = n.z;
    }
  const sb::core::ImageF v = exact.image(positions, normals);
  int soft = 0, dark = 0;
  for (size_t i = 0; i < v.data.size(); ++i) {
    if (!(positions.data[i * 4 + 3] > 0.5f)) {
      EXPECT_EQ(v.data[i], 1.0f);
      continue;
    }
    const float own = float(exact.visibility(
        glm::dvec3(positions.data[i * 4], positions.data[i * 4 + 1], positions.data[i * 4 + 2]),
        glm::dvec3(normals.data[i * 3], normals.data[i * 3 + 1], normals.data[i * 3 + 2])));
    EXPECT_EQ(v.data[i], own) << "pixel " << i % kWidth << ", " << i / kWidth;
    soft += own > 0.0f && own < 1.0f;
    dark += own == 0.0f;
  }
  EXPECT_GT(soft, 200) << "too few pixels see a penumbra";
  EXPECT_GT(dark, 50) << "too few pixels in an umbra";
}

TEST(ReferenceExact, MasksAnalyticShapesAndLightsOfNoAreaAreNamedAsUnsupported) {
  sb::core::Scene masked = plate_scene(false);
  masked.meshes[0].alpha_mode = sb::core::AlphaMode::Mask;
  masked.meshes[0].base_color_texture = 0;
  EXPECT_NE(ExactVisibility(masked).unsupported().find("'plate' is alpha-masked"),
            std::string::npos);
  sb::core::Scene analytic = plate_scene(false);
  analytic.meshes[0].analytic = sb::core::AnalyticShape::sphere({0, 4, 0}, 1.0f);
  EXPECT_NE(ExactVisibility(analytic).unsupported().find("analytic"), std::string::npos);
  // A point light (a segment, one half zero, has an exact form:
  // test_linear_light.cpp).
  sb::core::Scene point = plate_scene(false);
  point.light.half_u = {0, 0, 0};
  point.light.half_v = {0, 0, 0};
  EXPECT_NE(ExactVisibility(point).unsupported().find("no area"), std::string::npos);
}

// sees_whole_light, the adaptive reference's proof that a lit pilot missed
// nothing, on ground points under the plate, the ground itself casting: it
// may only hold where the closed form says the plate hides nothing, and it
// must hold where the plate's projection misses the light by more than its
// 1e-5 safety margin (the ground the point lies on never defeats it).
TEST(ReferenceExact, SeesTheWholeLightExactlyWhereThePlateHidesNothingOfIt) {
  sb::core::Scene scene = plate_scene(true);
  scene.meshes[1].casts_shadow = true;
  const ExactVisibility exact(scene);
  int proven = 0, hidden = 0;
  for (int i = 0; i <= 200; ++i)
    for (int j = 0; j <= 200; ++j) {
      const double x = -6.0 + 0.06 * i, z = -6.0 + 0.061 * j;
      const double eps = 0x1p-16 * std::max({std::abs(x), std::abs(z), 20.0});
      const glm::dvec3 surface(x, 0.0, z), origin(x, eps, z);
      const bool proof = exact.sees_whole_light(surface, origin, {0, 1, 0});
      // The plate's projection from the origin onto the light's plane.
      const double k = (10.0 - eps) / (4.0 - eps);
      const double ax = x + (-0.7 - x) * k, bx = x + (1.1 - x) * k;
      const double az = z + (-1.3 - z) * k, bz = z + (0.4 - z) * k;
      const double gap = std::max({ax - 1.0, -1.0 - bx, az - 1.0, -1.0 - bz});
      if (plate_visibility(x, eps, z) < 1.0) {
        ++hidden;
        EXPECT_FALSE(proof) << "x " << x << " z " << z;
      } else if (gap > 1e-3) {
        ++proven;
        EXPECT_TRUE(proof) << "x " << x << " z " << z << " gap " << gap;
      }
    }
  EXPECT_GT(hidden, 1000);
  EXPECT_GT(proven, 10000);
}

// Below the tangent plane the surface hides the light itself; no caster.
TEST(ReferenceExact, SeesTheWholeLightOnlyWhenAllOfItIsAboveTheSurface) {
  sb::core::Scene scene;
  scene.light = sbtest::square_light();
  const ExactVisibility exact(scene);
  const glm::dvec3 surface(0.3, 2.0, -0.4), up(0, 1, 0);
  EXPECT_TRUE(exact.sees_whole_light(surface, surface + 1e-4 * up, up));
  // Tilted until the plane through p meets y = 10 at x = 0: half the light below.
  const glm::dvec3 half = glm::normalize(glm::dvec3(8.0, 0.3, 0.0));
  EXPECT_FALSE(exact.sees_whole_light(surface, surface + 1e-4 * half, half));
  // An origin not above the surface is not a ray origin of this surface.
  EXPECT_FALSE(exact.sees_whole_light(surface, surface, up));
  EXPECT_FALSE(exact.sees_whole_light(surface, surface - 1e-4 * up, up));
}

// A small blocker beside the pyramid from (0, 1e-4, 0) to the light: where
// it is far enough out the proof holds; inside by a hair, or outside by
// less than the margin, it does not (a float ray could graze it). At y = 5
// the margin is about 6e-6: 5e-6 from the wider light, 1.2e-6 from the
// apex set back.
TEST(ReferenceExact, SeesTheWholeLightPastABlockerOnlyBeyondTheMargin) {
  const glm::dvec3 surface(0, 0, 0), origin(0, 1e-4, 0), up(0, 1, 0);
  // The pyramid's side x = +1 at y = 10 crosses y = 5 at about x = 0.5.
  const double side = (5.0 - origin.y) / (10.0 - origin.y);
  for (const auto& [offset, expected] :
       {std::pair{1e-2, true}, {1e-4, true}, {3e-6, false}, {-1e-9, false}, {-1e-2, false}}) {
    const float x0 = float(side + offset);
    sb::core::Scene scene;
    scene.light = sbtest::square_light();
    scene.meshes.push_back(sbtest::quad("blocker", {x0, 5, -0.2f}, {x0 + 0.3f, 5, -0.2f},
                                        {x0 + 0.3f, 5, 0.2f}, {x0, 5, 0.2f}, true));
    const ExactVisibility exact(scene);
    EXPECT_EQ(exact.sees_whole_light(surface, origin, up), expected) << "offset " << offset;
  }
}

// Seen from far to the side, rays reach the light's edge at a grazing
// angle. From (-20, 1e-4, 0) the ray to the light's edge x = 1 crosses
// y = 9.999 at x = 0.9979002: a blocker there from x = 0.997897 on hides a
// sliver of the light (the exact visibility says so), and one from 0.9981
// on hides nothing.
TEST(ReferenceExact, SeesTheWholeLightNotPastABlockerAtTheLightsEdgeSeenAtAGrazingAngle) {
  const glm::dvec3 surface(-20, 0, 0), origin(-20, 1e-4, 0), up(0, 1, 0);
  const auto blocker_from = [](float x0) {
    sb::core::Scene scene;
    scene.light = sbtest::square_light();
    scene.meshes.push_back(sbtest::quad("blocker", {x0, 9.999f, -0.5f}, {1.5f, 9.999f, -0.5f},
                                        {1.5f, 9.999f, 0.5f}, {x0, 9.999f, 0.5f}, true));
    return scene;
  };
  const ExactVisibility in_the_way(blocker_from(0.997897f));
  EXPECT_LT(in_the_way.visibility(surface, up), 1.0);
  EXPECT_FALSE(in_the_way.sees_whole_light(surface, origin, up));
  const ExactVisibility clear(blocker_from(0.9981f));
  EXPECT_EQ(clear.visibility(surface, up), 1.0);
  EXPECT_TRUE(clear.sees_whole_light(surface, origin, up));
}

TEST(ReferenceExact, SeesTheWholeLightNeverForASegmentOrAPointLight) {
  sb::core::Scene segment;
  segment.light = sbtest::square_light();
  segment.light.half_v = {0, 0, 0};
  EXPECT_FALSE(ExactVisibility(segment).sees_whole_light({0, 0, 0}, {0, 1e-4, 0}, {0, 1, 0}));
  sb::core::Scene point;
  point.light = sbtest::square_light();
  point.light.half_u = {0, 0, 0};
  point.light.half_v = {0, 0, 0};
  EXPECT_FALSE(ExactVisibility(point).sees_whole_light({0, 0, 0}, {0, 1e-4, 0}, {0, 1, 0}));
}

// The shadow of a convex box from p, on the light's plane y = 10: the convex
// hull of its eight corners projected from p (all between p and the plane).
// Returns the least distance by which the light's corners lie inside that
// hull (negative: some corner outside): the margin of an umbra.
double box_umbra_margin(const glm::dvec3& p, const glm::dvec3& lo, const glm::dvec3& hi) {
  std::vector<glm::dvec2> pts;
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 v((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
    const double k = (10.0 - p.y) / (v.y - p.y);
    pts.push_back({p.x + (v.x - p.x) * k, p.z + (v.z - p.z) * k});
  }
  // Andrew's monotone chain, counter-clockwise.
  std::sort(pts.begin(), pts.end(), [](const glm::dvec2& a, const glm::dvec2& b) {
    return a.x < b.x || (a.x == b.x && a.y < b.y);
  });
  const auto cross = [](const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<glm::dvec2> hull;
  for (int pass = 0; pass < 2; ++pass) {
    const size_t start = hull.size();
    for (const glm::dvec2& q : pts) {
      while (hull.size() >= start + 2 && cross(hull[hull.size() - 2], hull.back(), q) <= 0.0)
        hull.pop_back();
      hull.push_back(q);
    }
    hull.pop_back();
    std::reverse(pts.begin(), pts.end());
  }
  double margin = std::numeric_limits<double>::infinity();
  for (const glm::dvec2 corner :
       {glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(1, 1), glm::dvec2(-1, 1)})
    for (size_t i = 0; i < hull.size(); ++i) {
      const glm::dvec2 a = hull[i], b = hull[(i + 1) % hull.size()];
      margin = std::min(margin, cross(a, b, corner) / glm::length(b - a));
    }
  return margin;
}

// hides_whole_light, the proof that an occluded pilot missed nothing, on
// ground points under a closed box (the ground casting too, as open
// geometry): it may only hold where the box's projected hull covers the
// whole light, and must hold where it covers it with room to spare.
TEST(ReferenceExact, HidesTheWholeLightExactlyWhereABoxCoversAllOfIt) {
  const glm::dvec3 lo(-1.5, 3.0, -1.2), hi(1.7, 3.6, 1.4);
  sb::core::Scene scene;
  scene.light = sbtest::square_light();
  scene.meshes.push_back(box("box", glm::vec3(lo), glm::vec3(hi)));
  scene.meshes.push_back(
      sbtest::quad("ground", {-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}, true));
  const ExactVisibility exact(scene, {true, false});
  int proven = 0, umbra = 0;
  for (int i = 0; i <= 160; ++i)
    for (int j = 0; j <= 160; ++j) {
      const double x = -4.0 + 0.05 * i, z = -4.0 + 0.051 * j;
      const double eps = 0x1p-16 * 20.0;
      const glm::dvec3 surface(x, 0.0, z), origin(x, eps, z);
      const bool proof = exact.hides_whole_light(surface, origin, {0, 1, 0});
      const double margin = box_umbra_margin(origin, lo, hi);
      if (proof) {
        ++proven;
        EXPECT_GT(margin, 0.0) << "x " << x << " z " << z;
        EXPECT_EQ(exact.visibility(surface, {0, 1, 0}), 0.0) << "x " << x << " z " << z;
      }
      if (margin > 1e-3) {
        ++umbra;
        EXPECT_TRUE(proof) << "x " << x << " z " << z << " margin " << margin;
      }
    }
  EXPECT_GT(umbra, 2000);
  EXPECT_GE(proven, umbra);
}

// The horizon alone, a point inside a closed caster, and what proves
// nothing: an open quad however large, a light partly below the horizon.
TEST(ReferenceExact, HidesTheWholeLightBelowTheHorizonInsideACasterAndNowhereElse) {
  sb::core::Scene scene;
  scene.light = sbtest::square_light();
  scene.meshes.push_back(box("box", {-0.5f, 1.0f, -0.5f}, {0.5f, 2.0f, 0.5f}));
  scene.meshes.push_back(
      sbtest::quad("plate", {-9, 5, -9}, {9, 5, -9}, {9, 5, 9}, {-9, 5, 9}, true));
  const ExactVisibility exact(scene, {true, false});
  const glm::dvec3 up(0, 1, 0), down(0, -1, 0);
  // Facing away from the light: all of it below the horizon.
  EXPECT_TRUE(exact.hides_whole_light({3, 0, 0}, {3, -1e-4, 0}, down));
  // Tilted so that the plane through (3, 0, 0) meets y = 10 at x = 0, half
  // the light below it: no proof.
  const glm::dvec3 half = glm::normalize(glm::dvec3(10.0, 3.0, 0.0));
  EXPECT_FALSE(exact.hides_whole_light({3, 0, 0}, glm::dvec3(3, 0, 0) + 1e-4 * half, half));
  // Inside the box, facing up.
  EXPECT_TRUE(exact.hides_whole_light({0.1, 1.5, 0.2}, {0.1, 1.5001, 0.2}, up));
  // Under the open plate only (beside the box): it covers the light, but an
  // open caster proves nothing.
  EXPECT_EQ(exact.visibility({3, 0, 0}, up), 0.0);
  EXPECT_FALSE(exact.hides_whole_light({3, 0, 0}, {3, 1e-4, 0}, up));
}

}  // namespace
