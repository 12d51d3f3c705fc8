// PointBoxTree answers "is any point more than `depth` below this plane?"
// exactly: the same answer as looking at every point, on clouds made to
// put points near the threshold, and on the degenerate ones (one spot,
// one point, none).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "scenes/point_box_tree.h"

namespace sb {
namespace {

bool any_below_by_scan(const std::vector<glm::vec3>& points, const glm::dvec3& n, double d,
                       double depth) {
  for (const glm::vec3& p : points)
    if (glm::dot(n, glm::dvec3(p)) + d < -depth) return true;
  return false;
}

TEST(PointBoxTree, AgreesWithAScanOfEveryPoint) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coord(-10.0f, 10.0f);
  std::normal_distribution<double> gauss(0.0, 1.0);
  int below = 0, above = 0;
  for (int cloud = 0; cloud < 20; ++cloud) {
    // Clouds of 1 to ~5,000 points, some flat (a ground of z = 0).
    std::vector<glm::vec3> points(size_t(1 + cloud * cloud * 12));
    for (auto& p : points)
      p = glm::vec3(coord(rng), coord(rng), cloud % 3 == 0 ? 0.0f : coord(rng));
    const PointBoxTree tree(points);
    ASSERT_EQ(tree.size(), points.size());
    for (int q = 0; q < 200; ++q) {
      const glm::dvec3 n = glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)));
      // Planes through a point of the cloud, or through its lowest point
      // along n (a ground under it), shifted a little: the answer is then
      // decided by the points nearest the threshold.
      double lowest = glm::dot(n, glm::dvec3(points[0]));
      for (const glm::vec3& p : points) lowest = std::min(lowest, glm::dot(n, glm::dvec3(p)));
      const double on =
          q % 2 == 0 ? lowest : glm::dot(n, glm::dvec3(points[size_t(q) % points.size()]));
      const double d = -on + 0.001 * gauss(rng);
      const double depth = 1e-3;
      const bool expected = any_below_by_scan(points, n, d, depth);
      EXPECT_EQ(tree.any_below(n, d, depth), expected) << "cloud " << cloud << " query " << q;
      (expected ? below : above) += 1;
    }
  }
  // Both answers were asked for, many times.
  EXPECT_GT(below, 500);
  EXPECT_GT(above, 500);
}

TEST(PointBoxTree, PointsInOneSpotAndEmptySets) {
  const PointBoxTree same(std::vector<glm::vec3>(1000, glm::vec3(1.0f, 2.0f, 3.0f)));
  const glm::dvec3 up(0.0, 0.0, 1.0);
  EXPECT_FALSE(same.any_below(up, -3.0, 0.0));   // on the plane
  EXPECT_TRUE(same.any_below(up, -3.5, 0.1));    // 0.5 below
  EXPECT_FALSE(same.any_below(up, -3.05, 0.1));  // 0.05 below: within depth
  EXPECT_FALSE(PointBoxTree({}).any_below(up, 0.0, 0.0));
}

}  // namespace
}  // namespace sb
