// The shadow rays' start offset against small objects in a large scene: a
// 5 cm cube resting on a 300×300 ground, lit from 45° by a small light. Its
// contact shadow is pure geometry (V = 0 or 1 exactly), and so is the
// absence of self-shadowing on the faces that see the whole light. Every
// Embree ISA the CPU runs, since the kernels round differently.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "reference/embree_isa.h"
#include "reference/embree_scene.h"
#include "reference/ray_offset.h"
#include "reference/reference.h"
#include "scenes/mesh_builders.h"
#include "test_scenes.h"

namespace {

namespace ref = sb::reference;
using sb::core::ImageF;

constexpr float kHalf = 0.025f;  // the cube's half side: 5 cm on a 300 m ground

// Light 0.2×0.2 at (−10, 10, 0): 45° above the −x horizon, so the cube's
// shadow falls towards +x. A second, tilted cube floats at z = 1.
sb::core::Scene cube_on_huge_ground(bool ground_casts = false) {
  sb::core::Scene s;
  s.meshes.push_back(sbtest::quad("ground", {-150, 0, -150}, {-150, 0, 150}, {150, 0, 150},
                                  {150, 0, -150}, ground_casts));
  s.meshes.push_back(sb::make_box("cube", {0, kHalf, 0}, glm::vec3(kHalf)));
  const glm::mat3 tilt(glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1, 2, 3))));
  s.meshes.push_back(sb::make_box("tilted", {0, 0.2f, 1}, glm::vec3(kHalf), tilt));
  s.light.center = {-10, 10, 0};
  s.light.half_u = {0.1f, 0, 0};
  s.light.half_v = {0, 0, 0.1f};
  s.light.target = {0, 0, 0};
  return s;
}

struct Point {
  glm::vec3 p, n;
};

// A hand-made G-buffer, one point per pixel in a row.
std::pair<sb::core::ImageF, sb::core::ImageF> gbuffer(const std::vector<Point>& points) {
  sb::core::ImageF pos(int(points.size()), 1, 4), nrm(int(points.size()), 1, 3);
  for (size_t i = 0; i < points.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      pos.data[i * 4 + size_t(c)] = points[i].p[c];
      nrm.data[i * 3 + size_t(c)] = points[i].n[c];
    }
    pos.data[i * 4 + 3] = 1.0f;
  }
  return {pos, nrm};
}

// Points on a mesh's triangles, interpolated in float as a G-buffer would,
// with the triangle's own normal, where all four light corners lie strictly
// above the triangle's plane: on a convex solid nothing can block them.
std::vector<Point> fully_lit_points(const sb::core::Mesh& m, const sb::core::AreaLight& light) {
  const glm::vec3 corners[4] = {light.point(0, 0), light.point(1, 0), light.point(0, 1),
                                light.point(1, 1)};
  const float bary[][2] = {{0.2f, 0.3f}, {0.45f, 0.45f}, {0.1f, 0.8f}, {0.6f, 0.05f}};
  std::vector<Point> out;
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                    c = m.positions[m.indices[t + 2]];
    const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
    for (const auto& uv : bary) {
      const glm::vec3 p = (1.0f - uv[0] - uv[1]) * a + uv[0] * b + uv[1] * c;
      if (std::all_of(std::begin(corners), std::end(corners),
                      [&](const glm::vec3& l) { return glm::dot(l - p, n) > 1e-3f; }))
        out.push_back({p, n});
    }
  }
  return out;
}

class referenceOffset : public ::testing::TestWithParam<std::string> {
 protected:
  ref::Result trace(const sb::core::Scene& s, const std::vector<Point>& points) {
    const auto [pos, nrm] = gbuffer(points);
    return ref::compute(s, pos, nrm, {256, 1, "isa=" + GetParam()});
  }
  void expect_contact_shadow(const sb::core::Scene& s) {
    const glm::vec3 up(0, 1, 0);
    std::vector<Point> dark, lit;
    for (float d : {0.002f, 0.01f, 0.02f, 0.03f, 0.035f, 0.04f, 0.045f})
      for (float z : {0.0f, 0.015f, -0.015f}) dark.push_back({{kHalf + d, 0, z}, up});
    for (float d : {0.06f, 0.1f, 0.5f}) lit.push_back({{kHalf + d, 0, 0}, up});
    lit.push_back({{50, 0, 50}, up});
    lit.push_back({{-140, 0, -120}, up});
    lit.push_back({{140, 0, 0}, up});
    const ref::Result rd = trace(s, dark);
    for (size_t i = 0; i < dark.size(); ++i) {
      EXPECT_EQ(rd.visibility.data[i], 0.0f)
          << "ground point " << dark[i].p.x << "," << dark[i].p.z << " in the contact shadow";
    }
    const ref::Result rl = trace(s, lit);
    for (size_t i = 0; i < lit.size(); ++i) {
      EXPECT_EQ(rl.visibility.data[i], 1.0f) << "ground point " << lit[i].p.x << "," << lit[i].p.z;
    }
  }
  void SetUp() override {
    if (!ref::cpu_supports_isa(GetParam()))
      GTEST_SKIP() << "this CPU lacks " << GetParam() << " (it runs at most " << ref::best_cpu_isa()
                   << ")";
  }
};

// Ground points up to 4.5 cm beyond the cube's lit-away face: every segment
// to the light (x_l in [−10.1, −9.9]) crosses the plane x = 0.025 at height
// 10·d/(10.025 + d − (x_l + 10)) <= 0.0402 < 0.05, inside the face: V = 0.
// From 6 cm on it passes above the cube (>= 0.059): V = 1. Far ground points
// are lit too. The same holds when the ground casts, whose points then start
// 150·2^-16 = 0.0023 up (0.021 before, from every point: the old offset
// scaled with the scene's radius and lost the shadow from 3 cm on).
TEST_P(referenceOffset, ContactShadowOfASmallCubeOnAHugeGround) {
  for (bool ground_casts : {false, true}) {
    SCOPED_TRACE(ground_casts ? "casting ground" : "receiving ground");
    expect_contact_shadow(cube_on_huge_ground(ground_casts));
  }
}

// A huge caster tilted 20°, points within 0.1 of the origin on it: their
// own coordinates are small, but Embree's hit test rounds in the triangle's
// (up to 150). An offset from |p| alone left 40 (sse2 to avx) and 395 (avx2)
// of these 1600 points self-shadowed. The light is entirely above the
// plane: V = 1.
TEST_P(referenceOffset, NoSelfShadowNearTheOriginOfAHugeTiltedCaster) {
  const glm::dvec3 n(0, std::cos(0.35), std::sin(0.35)), e1(1, 0, 0), e2 = glm::cross(n, e1);
  const auto at = [&](double u, double v) { return glm::vec3(u * e1 + v * e2); };
  sb::core::Scene s;
  s.meshes.push_back(
      sbtest::quad("tilted", at(-150, -150), at(-150, 150), at(150, 150), at(150, -150), true));
  s.light = sbtest::square_light();
  std::vector<Point> points;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
      points.push_back({at(0.005 * (i - 19.5), 0.005 * (j - 19.5)), glm::vec3(n)});
  const ref::Result r = trace(s, points);
  int shadowed = 0;
  for (const float v : r.visibility.data) shadowed += v < 1.0f;
  EXPECT_EQ(shadowed, 0) << "of " << points.size();
}

// Faces that see the whole light above their plane: the top and the −x face
// of the resting cube, and whichever faces of the tilted one do.
TEST_P(referenceOffset, NoSelfShadowOnTheSmallCubesLitFaces) {
  const sb::core::Scene s = cube_on_huge_ground();
  std::vector<Point> points = fully_lit_points(s.meshes[1], s.light);
  const size_t resting = points.size();
  const std::vector<Point> tilted = fully_lit_points(s.meshes[2], s.light);
  points.insert(points.end(), tilted.begin(), tilted.end());
  ASSERT_EQ(resting, 2u * 2u * 4u);  // two faces, two triangles each
  ASSERT_GE(tilted.size(), 8u);
  const ref::Result r = trace(s, points);
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(r.visibility.data[i], 1.0f)
        << (i < resting ? "resting" : "tilted") << " cube at " << points[i].p.x << ","
        << points[i].p.y << "," << points[i].p.z;
  }
}

// The offset follows the point and the caster triangles it lies on: the
// huge ground changes it only for its own points, and only when it casts.
TEST(referenceOffsetScale, FollowsThePointAndItsOwnTrianglesOnly) {
  namespace d = ref::detail;
  for (bool ground_casts : {false, true}) {
    SCOPED_TRACE(ground_casts ? "casting ground" : "receiving ground");
    const sb::core::Scene s = cube_on_huge_ground(ground_casts);
    d::Device device("sse2");
    const d::FlatScene casters(device, s, [](const sb::core::Mesh& m) { return m.casts_shadow; });
    const d::RayOffset offset(s, casters);
    // On the cube's top: its vertices' largest coordinate is 0.05.
    EXPECT_EQ(offset.at({0.01f, 2 * kHalf, -0.005f}), d::kOffsetRelative * 2 * kHalf);
    // On the ground: its own coordinates (150) if it casts, else p's alone.
    EXPECT_EQ(offset.at({0.5f, 0, -0.25f}), d::kOffsetRelative * (ground_casts ? 150.0f : 0.5f));
    // In mid-air beside the cube: nothing but p.
    EXPECT_EQ(offset.at({0.2f, 0.01f, 0.1f}), d::kOffsetRelative * 0.2f);
  }
}

// Both references offset by the same rule: with a caster 20 km away, the
// exact reference once looked from 2^-16 of the casters' largest coordinate
// (0.31) above every point, over the 5 cm cube, and lost its contact
// shadow. On ground points beside the cube and on its faces, exact and
// 1024-spp Monte Carlo agree within four standard errors (one sample's
// weight where the stated error is 0).
TEST(referenceOffsetScale, TheExactReferenceSharesItBesideACasterFarAway) {
  sb::core::Scene s = cube_on_huge_ground();
  s.meshes.push_back(sb::make_box("far", {20000, 1, 0}, glm::vec3(1.0f)));
  std::vector<Point> points = fully_lit_points(s.meshes[1], s.light);
  const glm::vec3 up(0, 1, 0);
  for (int i = 0; i < 24; ++i)
    for (int j = 0; j < 9; ++j)
      points.push_back({{kHalf + 0.002f + 0.006f * float(i), 0, 0.01f * float(j - 4)}, up});
  // The penumbra behind the top edge: d = 0.0499 to 0.0509 (see above).
  for (int i = 0; i < 30; ++i)
    for (const float z : {-0.01f, 0.0f, 0.01f})
      points.push_back({{kHalf + 0.0495f + 0.00005f * float(i), 0, z}, up});
  const auto [pos, nrm] = gbuffer(points);
  ref::Settings exact_settings;
  exact_settings.exact = true;
  const ref::Result exact = ref::compute(s, pos, nrm, exact_settings);
  ASSERT_EQ(exact.method, ref::kExactMethod) << exact.exact_fallback;
  constexpr int kSpp = 1024;
  const ref::Result mc = ref::compute(s, pos, nrm, {kSpp, 1});
  int dark = 0, soft = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const double e = exact.visibility.data[i], m = mc.visibility.data[i];
    dark += m == 0.0;
    soft += m > 0.0 && m < 1.0;
    EXPECT_LE(std::abs(e - m), 4.0 * std::max(double(mc.std_error.data[i]), 1.0 / kSpp))
        << "point " << points[i].p.x << "," << points[i].p.y << "," << points[i].p.z << ": exact "
        << e << ", Monte Carlo " << m;
  }
  EXPECT_GT(dark, 40);
  EXPECT_GT(soft, 10);
}

INSTANTIATE_TEST_SUITE_P(EveryEmbreeIsa, referenceOffset,
                         ::testing::Values("sse2", "sse4.2", "avx", "avx2", "avx512"),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           std::string name = param.param;
                           name.erase(std::remove(name.begin(), name.end(), '.'), name.end());
                           return name;
                         });

}  // namespace
