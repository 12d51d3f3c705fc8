// The bound around several pyramids to a rectangular light
// (harness/reference/pyramids_bound.h), against each pyramid's own clip: a
// triangle that any of the pyramids meets is kept, and so is its box.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "reference/clipping.h"
#include "reference/light_frame.h"
#include "reference/pyramids_bound.h"

namespace {

using sb::reference::detail::Frame;
using sb::reference::detail::PyramidsBound;

glm::dvec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> g;
  while (true) {
    const glm::dvec3 d(g(rng), g(rng), g(rng));
    if (glm::length(d) > 1e-3) return glm::normalize(d);
  }
}

TEST(ReferencePyramidsBound, KeepsEveryTriangleThatOneOfThePyramidsMeetsAndItsBox) {
  std::mt19937 rng(65);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  size_t met = 0, culled = 0, culled_triangles = 0;
  for (int trial = 0; trial < 300; ++trial) {
    // A light of any size and orientation.
    sb::core::AreaLight light;
    const glm::dvec3 u = random_unit(rng);
    const glm::dvec3 v = glm::normalize(glm::cross(u, random_unit(rng)));
    light.center = glm::vec3(glm::dvec3(4.0 * unit(rng) - 2.0, 5.0 + 3.0 * unit(rng), 0.0));
    light.half_u = glm::vec3(u * (0.05 + 2.0 * unit(rng)));
    light.half_v = glm::vec3(v * (0.05 + 2.0 * unit(rng)));
    const Frame f(light);
    // Points near each other (a tile of one surface), or scattered (a tile
    // across a depth discontinuity), some beyond the light's plane.
    const double spread = std::pow(10.0, -3.0 + 4.0 * unit(rng));
    const glm::dvec3 around(4.0 * unit(rng) - 2.0, 3.0 * unit(rng), 4.0 * unit(rng) - 2.0);
    std::vector<glm::dvec3> points(1 + size_t(unit(rng) * 64.0));
    for (glm::dvec3& p : points) p = around + spread * random_unit(rng) * unit(rng);
    const PyramidsBound bound(f, points.data(), points.size(), 10.0);
    for (int k = 0; k < 400; ++k) {
      // Triangles of every size, around the light and the points.
      const double size = std::pow(10.0, -3.0 + 3.5 * unit(rng));
      const glm::dvec3 c =
          glm::mix(around, f.centre, unit(rng)) + 3.0 * random_unit(rng) * unit(rng);
      const glm::dvec3 a = c + size * random_unit(rng), b = c + size * random_unit(rng),
                       d = c + size * random_unit(rng);
      const glm::dvec3 lo = glm::min(a, glm::min(b, d)), hi = glm::max(a, glm::max(b, d));
      const bool kept = bound.may_meet(lo, hi), kept_triangle = bound.may_meet(a, b, d);
      culled += !kept;
      culled_triangles += !kept_triangle;
      for (const glm::dvec3& p : points) {
        if (!sb::reference::detail::triangle_meets(a, b, d, sb::reference::detail::pyramid(f, p)))
          continue;
        ++met;
        EXPECT_TRUE(kept) << "trial " << trial << ", triangle " << k;
        EXPECT_TRUE(kept_triangle) << "trial " << trial << ", triangle " << k;
        break;
      }
    }
  }
  // Both answers happen often, or the test shows nothing.
  EXPECT_GT(met, 10000u);
  EXPECT_GT(culled, 10000u);
  EXPECT_GT(culled_triangles, culled);
}

// Every pyramid's own points (its apex, the light's corners, a point
// inside) lie in the bound, even for a single point or coincident points.
TEST(ReferencePyramidsBound, KeepsThePyramidsThemselves) {
  sb::core::AreaLight light;
  light.center = {0, 10, 0};
  light.half_u = {1, 0, 0};
  light.half_v = {0, 0, 1};
  const Frame f(light);
  for (const std::vector<glm::dvec3>& points : std::vector<std::vector<glm::dvec3>>{
           {{0.5, 0.0, -0.2}},
           {{3.0, 1.0, 2.0}, {3.0, 1.0, 2.0}},
           {{-4.0, 0.0, 0.0}, {4.0, 0.0, 0.0}, {0.0, 20.0, 0.0}}}) {
    const PyramidsBound bound(f, points.data(), points.size(), 10.0);
    for (const glm::dvec3& p : points) {
      EXPECT_TRUE(bound.may_meet(p, p));
      for (const glm::dvec3& c : f.corners()) {
        EXPECT_TRUE(bound.may_meet(c, c));
        const glm::dvec3 inside = (p + c + f.centre) / 3.0;
        EXPECT_TRUE(bound.may_meet(inside, inside));
      }
    }
  }
}

}  // namespace
