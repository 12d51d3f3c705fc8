// cascaded_shadow_map's CPU side (techniques/cascaded/cascade_fit.h): the
// practical splits against Zhang et al.'s closed form, the slice's bounding
// sphere against its corners, the stable fit's texel snapping and constant
// extent (Valient 2008) against the tight fit, which has neither, and the
// depth range reaching casters outside the slice. No GL.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cascaded/cascade_fit.h"

namespace sb::test {
namespace {

using techniques::cascaded::box_coords;
using techniques::cascaded::box_corners;
using techniques::cascaded::CameraFrustum;
using techniques::cascaded::CascadeBox;
using techniques::cascaded::fit_cascade;
using techniques::cascaded::FitMode;
using techniques::cascaded::plan_cascades;
using techniques::cascaded::practical_splits;
using techniques::cascaded::slice_bounding_sphere;
using techniques::cascaded::slice_corners;

// C_i = λ·n·(f/n)^(i/N) + (1−λ)·(n + (f−n)·i/N), in double.
double closed_form(double n, double f, int i, int count, double lambda) {
  return lambda * n * std::pow(f / n, double(i) / count) +
         (1.0 - lambda) * (n + (f - n) * double(i) / count);
}

TEST(PracticalSplits, MatchTheClosedFormAtLambdaZeroOneAndBetween) {
  const double n = 0.5, f = 120.0;
  for (int count : {1, 3, 4, 8})
    for (double lambda : {0.0, 0.25, 0.5, 0.8, 1.0}) {
      const std::vector<float> c = practical_splits(float(n), float(f), count, float(lambda));
      ASSERT_EQ(c.size(), size_t(count) + 1);
      for (int i = 0; i <= count; ++i)
        EXPECT_NEAR(c[size_t(i)], closed_form(n, f, i, count, lambda), 1e-5 * f)
            << "N " << count << " lambda " << lambda << " i " << i;
    }
}

TEST(PracticalSplits, LambdaOneIsGeometricAndLambdaZeroIsEvenlySpaced) {
  const std::vector<float> log = practical_splits(1.0f, 256.0f, 4, 1.0f);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(log[size_t(i) + 1] / log[size_t(i)], 4.0, 1e-4);
  const std::vector<float> uniform = practical_splits(1.0f, 257.0f, 4, 0.0f);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(uniform[size_t(i) + 1] - uniform[size_t(i)], 64.0, 1e-3);
}

CameraFrustum camera_at(const glm::vec3& eye, const glm::vec3& forward) {
  CameraFrustum c;
  c.view = glm::lookAt(eye, eye + forward, glm::vec3(0.0f, 1.0f, 0.0f));
  c.tan_half_fov_y = std::tan(glm::radians(22.5f));
  c.aspect = 4.0f / 3.0f;
  return c;
}

TEST(SliceBoundingSphere, HoldsEveryCornerAndTouchesOne) {
  const CameraFrustum cam =
      camera_at({1.0f, 2.0f, 3.0f}, glm::normalize(glm::vec3(0.3f, -0.2f, -1)));
  for (auto [d0, d1] : {std::pair{0.5f, 2.0f}, {2.0f, 9.0f}, {9.0f, 60.0f}}) {
    const auto s = slice_bounding_sphere(cam, d0, d1);
    float farthest = 0.0f;
    for (const glm::vec3& p : slice_corners(cam, d0, d1))
      farthest = std::max(farthest, glm::distance(p, s.center));
    EXPECT_LE(farthest, s.radius * (1.0f + 1e-5f));
    EXPECT_GE(farthest, s.radius * (1.0f - 1e-5f));
  }
}

constexpr int kSize = 512;
const glm::vec3 kSunDirection = glm::normalize(glm::vec3(0.4f, -1.0f, 0.25f));

std::array<glm::vec3, 8> caster_corners() { return box_corners({-20, 0, -40}, {20, 4, 5}); }

CascadeBox fit(const CameraFrustum& cam, FitMode mode) {
  return fit_cascade(cam, 4.0f, 15.0f, kSunDirection, caster_corners(), kSize, mode);
}

// The texel coordinates of a fixed world point in the map fitted for a
// camera moved by `shift`, less those for the unmoved camera.
glm::vec2 texel_motion(FitMode mode, const glm::vec3& shift) {
  const glm::vec3 forward = glm::normalize(glm::vec3(0.1f, -0.3f, -1.0f));
  const glm::vec3 eye{0.3f, 3.0f, 8.0f}, point{1.234f, 0.5f, -2.71f};
  const glm::vec3 a = box_coords(fit(camera_at(eye, forward), mode), point);
  const glm::vec3 b = box_coords(fit(camera_at(eye + shift, forward), mode), point);
  return (glm::vec2(b) - glm::vec2(a)) * float(kSize);
}

// Sub-texel and multi-texel camera moves (a texel here is about 0.04 units).
const glm::vec3 kShifts[] = {{0.013f, 0.0f, 0.0f},     {0.0f, 0.007f, 0.0f},  {0.0f, 0.0f, 0.021f},
                             {0.031f, -0.017f, 0.05f}, {0.37f, 0.11f, -0.2f}, {-1.3f, 0.4f, 0.9f}};

float distance_to_whole(float v) { return std::abs(v - std::round(v)); }

TEST(StableFit, AFixedWorldPointMovesInTheMapByWholeTexelsOnly) {
  for (const glm::vec3& shift : kShifts) {
    const glm::vec2 m = texel_motion(FitMode::Stable, shift);
    EXPECT_LT(distance_to_whole(m.x), 0.02f)
        << "shift " << shift.x << " " << shift.y << " " << shift.z;
    EXPECT_LT(distance_to_whole(m.y), 0.02f)
        << "shift " << shift.x << " " << shift.y << " " << shift.z;
  }
}

// The property above is not free: without snapping (the tight fit) the
// point slides by fractions of a texel.
TEST(TightFit, AFixedWorldPointSlidesByFractionsOfATexel) {
  float worst = 0.0f;
  for (const glm::vec3& shift : kShifts) {
    const glm::vec2 m = texel_motion(FitMode::Tight, shift);
    worst = std::max({worst, distance_to_whole(m.x), distance_to_whole(m.y)});
  }
  EXPECT_GT(worst, 0.1f);
}

// The extent (the box's side) under a camera turned about its eye.
std::vector<glm::vec2> extents_under_rotation(FitMode mode) {
  std::vector<glm::vec2> out;
  for (float yaw : {0.0f, 17.0f, 45.0f, 90.0f, 133.0f})
    for (float pitch : {-30.0f, -5.0f, 10.0f}) {
      const glm::quat q = glm::angleAxis(glm::radians(yaw), glm::vec3(0, 1, 0)) *
                          glm::angleAxis(glm::radians(pitch), glm::vec3(1, 0, 0));
      const CascadeBox b = fit(camera_at({0.3f, 3.0f, 8.0f}, q * glm::vec3(0, 0, -1)), mode);
      out.push_back(b.hi - b.lo);
    }
  return out;
}

TEST(StableFit, ItsExtentDoesNotChangeWithCameraRotation) {
  const std::vector<glm::vec2> e = extents_under_rotation(FitMode::Stable);
  for (const glm::vec2& x : e) {
    EXPECT_NEAR(x.x, e.front().x, 1e-5f * e.front().x);
    EXPECT_NEAR(x.y, e.front().x, 1e-5f * e.front().x);  // square
  }
}

TEST(TightFit, ItsExtentChangesWithCameraRotation) {
  const std::vector<glm::vec2> e = extents_under_rotation(FitMode::Tight);
  float spread = 0.0f;
  for (const glm::vec2& x : e) spread = std::max(spread, std::abs(x.x - e.front().x));
  EXPECT_GT(spread, 0.05f * e.front().x);
}

TEST(CascadeFit, TheSliceLiesInsideItsBoxForBothFits) {
  const CameraFrustum cam =
      camera_at({0.3f, 3.0f, 8.0f}, glm::normalize(glm::vec3(0.2f, -0.4f, -1)));
  for (FitMode mode : {FitMode::Stable, FitMode::Tight}) {
    const CascadeBox b = fit(cam, mode);
    for (const glm::vec3& p : slice_corners(cam, 4.0f, 15.0f)) {
      const glm::vec3 t = box_coords(b, p);
      for (int k = 0; k < 3; ++k) {
        EXPECT_GE(t[k], -1e-4f);
        EXPECT_LE(t[k], 1.0f + 1e-4f);
      }
    }
  }
}

// A caster far towards the sun from the slice, outside it, still lands in
// the map's depth range (window depth >= 0), so its shadow is not clipped away.
TEST(CascadeFit, TheDepthRangeReachesCastersOutsideTheSlice) {
  const CameraFrustum cam =
      camera_at({0.3f, 3.0f, 8.0f}, glm::normalize(glm::vec3(0.0f, -0.4f, -1)));
  const glm::vec3 receiver = slice_corners(cam, 4.0f, 15.0f)[4];
  const glm::vec3 caster = receiver - kSunDirection * 30.0f;  // 30 units up the sun's ray
  const auto corners = box_corners(caster - glm::vec3(0.5f), caster + glm::vec3(0.5f));
  for (FitMode mode : {FitMode::Stable, FitMode::Tight}) {
    const CascadeBox b = fit_cascade(cam, 4.0f, 15.0f, kSunDirection, corners, kSize, mode);
    const glm::vec3 t = box_coords(b, caster), r = box_coords(b, receiver);
    EXPECT_GE(t.z, 0.0f);
    EXPECT_LT(t.z, r.z);
    EXPECT_NEAR(t.x, r.x, 1e-4f);  // on the receiver's texel: it shadows it
    EXPECT_NEAR(t.y, r.y, 1e-4f);
  }
}

TEST(PlanCascades, EachBoxCoversTheBandOfTheCascadeBeforeIt) {
  const CameraFrustum cam =
      camera_at({0.3f, 3.0f, 8.0f}, glm::normalize(glm::vec3(0.2f, -0.4f, -1)));
  const auto plan = plan_cascades(cam, 0.5f, 60.0f, 4, 0.5f, 0.2f, kSunDirection, caster_corners(),
                                  kSize, FitMode::Stable);
  ASSERT_EQ(plan.boxes.size(), 4u);
  EXPECT_EQ(plan.bands.back(), 0.0f);
  for (size_t i = 0; i + 1 < 4; ++i) {
    EXPECT_NEAR(plan.bands[i], 0.2f * (plan.splits[i + 1] - plan.splits[i]), 1e-5f);
    // The band's near end, seen in the next cascade's box.
    for (const glm::vec3& p :
         slice_corners(cam, plan.splits[i + 1] - plan.bands[i], plan.splits[i + 1])) {
      const glm::vec3 t = box_coords(plan.boxes[i + 1], p);
      EXPECT_GE(std::min(t.x, t.y), -1e-4f);
      EXPECT_LE(std::max(t.x, t.y), 1.0f + 1e-4f);
    }
  }
}

}  // namespace
}  // namespace sb::test
