// The light's own frame (common/light_frame.h) for each light shape: u and
// v along half_u and half_v (either sense), n towards the target,
// v = n × u; for a
// segment along half_v ([0, h]) v must run along it (u used to be picked
// arbitrarily, putting v up to 90° off the segment).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include "common/light_frame.h"
#include "core/scene_types.h"

namespace sb::techniques {

using core::AreaLight;
using core::make_area_light;

namespace {

void expect_orthonormal(const LightFrame& f) {
  EXPECT_NEAR(glm::length(f.u), 1.0f, 1e-5f);
  EXPECT_NEAR(glm::length(f.v), 1.0f, 1e-5f);
  EXPECT_NEAR(glm::length(f.n), 1.0f, 1e-5f);
  EXPECT_NEAR(glm::dot(f.u, f.v), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::dot(f.u, f.n), 0.0f, 1e-5f);
  // v = n × u, as the frame's header says.
  EXPECT_NEAR(glm::length(f.v - glm::cross(f.n, f.u)), 0.0f, 1e-5f);
}

TEST(LightFrame, EachShapeKeepsItsAxesAlongTheLightsSides) {
  // An oblique light, so that no axis is a world axis.
  const glm::vec3 centre(3.5f, 10.0f, 2.5f), target(0.0f);
  const glm::vec3 towards = glm::normalize(target - centre);
  for (const auto& [w, h] : {std::pair{2.0f, 1.0f}, std::pair{2.0f, 0.0f}, std::pair{0.0f, 3.0f},
                             std::pair{0.0f, 0.0f}}) {
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
    const AreaLight light = make_area_light(centre, target, w, h);
    const LightFrame f(light);
    expect_orthonormal(f);
    EXPECT_GT(glm::dot(f.n, towards), 0.99f);
    EXPECT_NEAR(f.half_width, 0.5f * w, 1e-5f);
    EXPECT_NEAR(f.half_height, 0.5f * h, 1e-5f);
    if (w > 0.0f) {
      EXPECT_GT(std::fabs(glm::dot(f.u, glm::normalize(light.half_u))), 0.9999f);
    }
    if (h > 0.0f) {
      EXPECT_GT(std::fabs(glm::dot(f.v, glm::normalize(light.half_v))), 0.9999f);
    }
    // Each corner is at (±half_width, ±half_height) in the frame (the
    // frame's v = n × u may point against half_v: the light is symmetric).
    const glm::vec3 corner = f.to_light(light.point(1.0f, 1.0f));
    EXPECT_NEAR(std::fabs(corner.x), f.half_width, 1e-4f);
    EXPECT_NEAR(std::fabs(corner.y), f.half_height, 1e-4f);
    EXPECT_NEAR(corner.z, 0.0f, 1e-4f);
  }
}

}  // namespace
}  // namespace sb::techniques
