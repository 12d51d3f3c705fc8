// Linear lights (AreaLight::is_segment(): `light.size: [w, 0]` or `[0, h]`)
// in both references, against closed forms, no GL:
//   - a half-plane occluder whose edge crosses the segment's shadow: from a
//     receiver point the visible fraction is where the plane through the
//     point and the edge meets the light's line; the Monte Carlo reference
//     matches it within four of its standard errors (one sample's weight
//     where the stated error is 0), is exactly 0 and 1 in umbra and lit
//     parts, and the exact reference matches it to 1e-6: along half_u, along
//     half_v, oblique to the edge, and tilted out of the plate's plane;
//   - stratifying along the segment: on the same segment the 2-D layout's
//     error (a rectangle 1e-6 deep) is several times larger;
//   - a segment parallel to the edge: a hard shadow, exactly 0 or 1 in both;
//   - exact against Monte Carlo on spheres and boxes;
//   - a point on the segment's line, the horizon, the 1-D union, and which
//     lights the exact reference takes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "reference/exact_visibility.h"
#include "reference/ray_offset.h"
#include "reference/reference.h"
#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"
#include "test_scenes.h"

namespace {

using sb::core::ImageF;
using sb::reference::ExactVisibility;
namespace ref = sb::reference;

// A segment light, `half` along half_u ([w, 0]) or half_v ([0, h]).
sb::core::AreaLight segment(glm::vec3 center, glm::vec3 half, bool along_v) {
  sb::core::AreaLight l;
  l.center = center;
  l.half_u = along_v ? glm::vec3(0.0f) : half;
  l.half_v = along_v ? half : glm::vec3(0.0f);
  l.target = {0, 0, 0};
  return l;
}

// A one-row G-buffer of ground points facing up.
struct Ground {
  sb::core::ImageF positions, normals;
  explicit Ground(const std::vector<glm::vec3>& points)
      : positions(int(points.size()), 1, 4, 0.0f), normals(int(points.size()), 1, 3, 0.0f) {
    for (size_t i = 0; i < points.size(); ++i) {
      for (int c = 0; c < 3; ++c) positions.at(int(i), 0, c) = points[i][c];
      positions.at(int(i), 0, 3) = 1.0f;
      normals.at(int(i), 0, 1) = 1.0f;
    }
  }
};

// A plate in the plane y = 5, bounded on one side by the line through `edge`
// along `along` and reaching 30 units into `across` and along the edge both
// ways: a half-plane for every ray in these tests. One open quad.
struct HalfPlane {
  std::string name;
  sb::core::Scene scene;
  HalfPlane(std::string label, const sb::core::AreaLight& light, glm::vec3 edge, glm::vec3 along,
            glm::vec3 across)
      : name(std::move(label)) {
    scene.light = light;
    scene.meshes.push_back(sbtest::quad("plate", edge - 30.0f * along, edge + 30.0f * along,
                                        edge + 30.0f * along + 30.0f * across,
                                        edge - 30.0f * along + 30.0f * across, true));
  }
  // The visible fraction of the segment seen from `eye`: the plane through
  // eye and the edge meets the light's line at s*; a light point is hidden
  // when it lies on the plate's side of that plane (the ray to it then meets
  // y = 5 on the plate's side of the edge).
  double fraction(const glm::dvec3& eye, double* crossing = nullptr) const {
    const auto& v = scene.meshes[0].positions;  // float corners, as both references see them
    const glm::dvec3 e0(v[0]), e1(v[1]), inside(v[2]);
    const glm::dvec3 normal = glm::cross(e1 - e0, e0 - eye);
    const double side = glm::dot(normal, inside - eye) > 0.0 ? 1.0 : -1.0;
    const glm::dvec3 a(scene.light.segment_end(0.0f)), b(scene.light.segment_end(1.0f));
    const double f0 = side * glm::dot(normal, a - eye), f1 = side * glm::dot(normal, b - eye);
    // Hidden where f(s) = f0 + s (f1 - f0) > 0.
    const double s = f0 / (f0 - f1);
    if (crossing) *crossing = s;
    if (f0 <= 0.0 && f1 <= 0.0) return 1.0;
    if (f0 > 0.0 && f1 > 0.0) return 0.0;
    return f0 <= 0.0 ? s : 1.0 - s;
  }
};

std::vector<HalfPlane> half_planes() {
  std::vector<HalfPlane> out;
  // [w, 0], the edge perpendicular to the segment.
  out.emplace_back("along half_u, edge across it", segment({0, 10, 0}, {1, 0, 0}, false),
                   glm::vec3(0.3f, 5, 0), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0));
  // [0, h]: the segment runs along half_v (z).
  out.emplace_back("along half_v", segment({0.2f, 10, -0.1f}, {0, 0, 1.5f}, true),
                   glm::vec3(0, 5, 0.25f), glm::vec3(1, 0, 0), glm::vec3(0, 0, -1));
  // The edge at 37 degrees to the segment.
  out.emplace_back("oblique to the edge", segment({0, 10, 0}, {1, 0, 0}, false), glm::vec3(0, 5, 0),
                   glm::vec3(0.8f, 0, 0.6f), glm::vec3(0.6f, 0, -0.8f));
  // Tilted out of the horizontal, oblique, along half_v.
  out.emplace_back("tilted and oblique", segment({-0.3f, 10, 0.4f}, {0.9f, 0.4f, 0.3f}, true),
                   glm::vec3(0.1f, 5, 0), glm::vec3(0.6f, 0, 0.8f), glm::vec3(-0.8f, 0, 0.6f));
  return out;
}

std::vector<glm::vec3> ground_grid(glm::vec2 lo, glm::vec2 hi, int nx, int nz) {
  std::vector<glm::vec3> out;
  for (int j = 0; j < nz; ++j)
    for (int i = 0; i < nx; ++i)
      out.emplace_back(lo.x + (hi.x - lo.x) * (float(i) + 0.5f) / float(nx), 0.0f,
                       lo.y + (hi.y - lo.y) * (float(j) + 0.5f) / float(nz));
  return out;
}

TEST(referenceLinearLight, MonteCarloMatchesTheHalfPlaneClosedForm) {
  constexpr int kSpp = 256;
  const std::vector<glm::vec3> points = ground_grid({-3, -3}, {3, 3}, 61, 61);
  const Ground g(points);
  for (const HalfPlane& hp : half_planes()) {
    ASSERT_TRUE(hp.scene.light.is_segment()) << hp.name;
    const ref::Result r = ref::compute(hp.scene, g.positions, g.normals, {kSpp, 5});
    int lit = 0, umbra = 0, penumbra = 0;
    double err2 = 0.0;
    for (size_t i = 0; i < points.size(); ++i) {
      const glm::dvec3 p(points[i]);
      // Monte Carlo's rays start kOffsetRelative * |p|inf above the ground
      // (no caster under them: ray_offset.h).
      const double eps =
          double(ref::detail::kOffsetRelative) * std::max(std::fabs(p.x), std::fabs(p.z));
      double s = 0.0;
      const double f = hp.fraction(p + glm::dvec3(0, eps, 0), &s);
      const double v = r.visibility.data[i], se = r.std_error.data[i];
      // Clear of the segment's ends by 1e-3: wholly lit or wholly hidden.
      const bool clear = s < -1e-3 || s > 1.0 + 1e-3;
      if (clear && f == 1.0) {
        ++lit;
        EXPECT_EQ(v, 1.0) << hp.name << ", point " << i;
        EXPECT_EQ(se, 0.0);
      } else if (clear && f == 0.0) {
        ++umbra;
        EXPECT_EQ(v, 0.0) << hp.name << ", point " << i;
        EXPECT_EQ(se, 0.0);
      } else if (f > 0.0 && f < 1.0) {
        ++penumbra;
        // Where the pair around the edge agrees the stated error is 0; one
        // sample's weight stands in (test_exact_agreement.cpp).
        EXPECT_LE(std::fabs(v - f), 4.0 * std::max(se, 1.0 / kSpp))
            << hp.name << ", point " << i << ": V " << v << ", closed form " << f;
        err2 += (v - f) * (v - f);
      }
    }
    const double rmse = std::sqrt(err2 / std::max(penumbra, 1));
    std::printf("%s: %d lit, %d umbra, %d penumbra points, RMSE %.2e = %.2f / spp\n",
                hp.name.c_str(), lit, umbra, penumbra, rmse, rmse * kSpp);
    EXPECT_GT(lit, 100) << hp.name;
    EXPECT_GT(umbra, 100) << hp.name;
    EXPECT_GT(penumbra, 300) << hp.name;
    // One stratum holds the edge: its sample errs by at most 1/N, the RMS
    // over the edge's place in it sqrt(1/6)/N.
    EXPECT_LT(rmse, 0.6 / kSpp) << hp.name;
  }
}

TEST(referenceLinearLight, ExactMatchesTheHalfPlaneClosedForm) {
  const std::vector<glm::vec3> points = ground_grid({-3, -3}, {3, 3}, 61, 61);
  const Ground g(points);
  for (const HalfPlane& hp : half_planes()) {
    const ExactVisibility exact(hp.scene);
    ASSERT_EQ(exact.unsupported(), "") << hp.name;
    ref::Settings settings;
    settings.exact = true;
    const ref::Result r = ref::compute(hp.scene, g.positions, g.normals, settings);
    EXPECT_EQ(r.method, ref::kExactMethod) << r.exact_fallback;
    double worst = 0.0;
    int penumbra = 0;
    for (size_t i = 0; i < points.size(); ++i) {
      const glm::dvec3 p(points[i]);
      // 2^-16 * max(|p|inf, M) above the ground, as Monte Carlo's rays
      // start: the ground is no caster, so M = 0.
      const double eps = 0x1p-16 * std::max(std::fabs(p.x), std::fabs(p.z));
      double s = 0.0;
      const double f = hp.fraction(p + glm::dvec3(0, eps, 0), &s);
      const double v = exact.visibility(p, {0, 1, 0});
      penumbra += f > 0.0 && f < 1.0;
      worst = std::max(worst, std::fabs(v - f));
      EXPECT_NEAR(v, f, 1e-6) << hp.name << ", point " << i;
      // Umbra and lit parts are not penumbra by a rounding error.
      if (s < -1e-3 || s > 1.0 + 1e-3) {
        EXPECT_EQ(v, f) << hp.name << ", point " << i;
      }
      EXPECT_NEAR(r.visibility.data[i], f, 1e-6) << hp.name << ", point " << i;
      EXPECT_EQ(r.std_error.data[i], 0.0f);
    }
    std::printf("%s: %d penumbra points, max |V - closed form| %.2e\n", hp.name.c_str(), penumbra,
                worst);
    EXPECT_GT(penumbra, 300) << hp.name;
  }
}

// A segment parallel to the edge casts a hard shadow: from every point it
// is wholly hidden or wholly seen. The exact reference's umbra must not
// read 1e-15 where the plate's two triangles' intervals meet (as it did on
// the plates scene before abutting intervals were joined).
TEST(referenceLinearLight, ASegmentAlongTheEdgeCastsAHardShadow) {
  const HalfPlane hp("along the edge", segment({-3, 8, 0}, {0, 0, 0.5f}, false),
                     glm::vec3(0, 1, 0.1f), glm::vec3(0, 0, 1), glm::vec3(-1, 0, 0));
  const std::vector<glm::vec3> points = ground_grid({-2, -2}, {2, 2}, 41, 41);
  const Ground g(points);
  ref::Settings exact_settings;
  exact_settings.exact = true;
  const ref::Result exact = ref::compute(hp.scene, g.positions, g.normals, exact_settings);
  const ref::Result mc = ref::compute(hp.scene, g.positions, g.normals, {64, 1});
  int lit = 0, umbra = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3 p(points[i]);
    const double f = hp.fraction(p);
    // The shadow's edge on the ground is x = 3/7 (from (-3, 8) over (0, 1)).
    if (std::fabs(p.x - 3.0 / 7.0) < 1e-3) continue;
    ASSERT_TRUE(f == 0.0 || f == 1.0) << f;
    (f == 0.0 ? umbra : lit)++;
    EXPECT_EQ(exact.visibility.data[i], f) << "point " << i;
    EXPECT_EQ(mc.visibility.data[i], f) << "point " << i;
  }
  EXPECT_GT(umbra, 400);
  EXPECT_GT(lit, 400);
}

// The point of the 1-D layout: on the segment of the first half-plane case,
// all points in its penumbra, against the same segment as a rectangle 1e-6
// deep (the 2-D layout, as every segment was sampled before; the edge runs
// across the segment, so the depth changes no V). The 2-D layout spends
// sqrt(N) rows on the axis with no extent, each row crossing the edge with
// one stratum: its error is about sqrt(rows) = N^(1/4) times larger, 4 at
// 256 spp, 5.7 at 1024.
TEST(referenceLinearLight, StratifyingAlongTheSegmentCutsTheError) {
  const HalfPlane segment_case = half_planes()[0];
  HalfPlane rectangle_case = segment_case;
  rectangle_case.scene.light.half_v = {0, 0, 1e-6f};
  ASSERT_FALSE(rectangle_case.scene.light.is_segment());
  // The penumbra on the ground runs from x = -0.4 to 1.6.
  const std::vector<glm::vec3> points = ground_grid({-0.35f, -2}, {1.55f, 2}, 80, 60);
  const Ground g(points);
  for (const int spp : {256, 1024}) {
    const ref::Result seg = ref::compute(segment_case.scene, g.positions, g.normals, {spp, 9});
    const ref::Result rect = ref::compute(rectangle_case.scene, g.positions, g.normals, {spp, 9});
    double e_seg = 0, e_rect = 0, se_seg = 0, se_rect = 0;
    for (size_t i = 0; i < points.size(); ++i) {
      const glm::dvec3 p(points[i]);
      const double eps =
          double(ref::detail::kOffsetRelative) * std::max(std::fabs(p.x), std::fabs(p.z));
      const double f = segment_case.fraction(p + glm::dvec3(0, eps, 0));
      ASSERT_GT(f, 0.0);
      ASSERT_LT(f, 1.0);
      e_seg += std::pow(seg.visibility.data[i] - f, 2);
      e_rect += std::pow(rect.visibility.data[i] - f, 2);
      se_seg += std::pow(seg.std_error.data[i], 2);
      se_rect += std::pow(rect.std_error.data[i], 2);
    }
    const double n = double(points.size());
    e_seg = std::sqrt(e_seg / n);
    e_rect = std::sqrt(e_rect / n);
    se_seg = std::sqrt(se_seg / n);
    se_rect = std::sqrt(se_rect / n);
    std::printf(
        "%d spp, %zu penumbra points: RMSE along the segment %.2e, 2-D layout %.2e (%.1fx); "
        "RMS stated error %.2e and %.2e (%.1fx)\n",
        spp, points.size(), e_seg, e_rect, e_rect / e_seg, se_seg, se_rect, se_rect / se_seg);
    RecordProperty("rmse_ratio_" + std::to_string(spp), std::to_string(e_rect / e_seg));
    const double expected = std::pow(double(spp), 0.25);
    EXPECT_GT(e_rect / e_seg, 0.8 * expected) << spp;
    EXPECT_GT(se_rect / se_seg, 0.8 * expected) << spp;
    // The stated error is still the right size (conservative: the pair's
    // disagreement has probability q where the sample's variance is q(1-q)).
    EXPECT_GT(e_seg / se_seg, 0.4) << spp;
    EXPECT_LT(e_seg / se_seg, 1.2) << spp;
  }
}

// Spheres and boxes (closed: only their near sides are kept) over a ground
// plane, under a segment along half_u and one along half_v; G-buffers from
// primary rays.
void expect_agreement(const sb::core::AreaLight& light, const std::string& label) {
  sb::core::Scene s;
  s.meshes.push_back(sb::make_ground_plane("ground", {0, 0, 0}, 8.0f));
  s.meshes.push_back(sb::make_uv_sphere("sphere", {-1.0f, 1.2f, 0.3f}, 0.7f, 24, 16));
  s.meshes.push_back(sb::make_uv_sphere("small sphere", {1.3f, 0.8f, -0.9f}, 0.45f, 20, 12));
  s.meshes.push_back(sb::make_box("box", {0.5f, 0.6f, 1.3f}, {0.35f, 0.6f, 0.3f}));
  const float c = std::cos(0.5f), sn = std::sin(0.5f);
  s.meshes.push_back(sb::make_box("slab", {0.1f, 1.9f, -0.4f}, {0.6f, 0.08f, 0.4f},
                                  glm::mat3(c, 0, -sn, 0, 1, 0, sn, 0, c)));
  s.light = light;
  s.camera.eye = {0.5f, 8.0f, 6.0f};
  s.camera.target = {0, 0, 0};
  s.camera.fov_y_degrees = 45.0f;
  const ref::GBuffer g = ref::trace_gbuffer(s, 160, 120);
  ref::Settings exact_settings;
  exact_settings.exact = true;
  const ref::Result exact = ref::compute(s, g.positions, g.normals, exact_settings);
  ASSERT_EQ(exact.method, ref::kExactMethod) << exact.exact_fallback;
  constexpr int kSpp = 256;
  const ref::Result mc = ref::compute(s, g.positions, g.normals, {kSpp, 2});
  size_t covered = 0, outside = 0, penumbra = 0;
  double worst = 0.0;
  for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
    if (!(g.positions.data[i * 4 + 3] > 0.5f)) continue;
    ++covered;
    const double v = exact.visibility.data[i];
    const double d = std::fabs(v - double(mc.visibility.data[i]));
    penumbra += v > 0.0 && v < 1.0;
    worst = std::max(worst, d);
    outside += d > 4.0 * std::max(double(mc.std_error.data[i]), 1.0 / kSpp);
  }
  std::printf(
      "%s: %zu covered px (%zu in the exact penumbra), %zu beyond 4 sigma, max |diff| %.4f\n",
      label.c_str(), covered, penumbra, outside, worst);
  EXPECT_GT(penumbra, 500u) << label;
  EXPECT_LE(double(outside), 0.001 * double(covered)) << label;
}

TEST(referenceLinearLight, ExactAgreesWithMonteCarloOnSpheresAndBoxes) {
  expect_agreement(segment({1.5f, 7, 1}, {1.2f, 0, -0.5f}, false), "segment along half_u");
  expect_agreement(segment({-1, 6, 0.5f}, {0.3f, 0.2f, 1.4f}, true), "segment along half_v");
}

// From a point on the segment's line there is no plane through it: the rays
// all run along the line, and the nearest crossing hides the rest.
TEST(referenceLinearLight, APointOnTheSegmentsLineSeesItEndOn) {
  sb::core::Scene s;
  s.light = segment({0, 10, 0}, {1, 0, 0}, false);  // x from -1 to 1 at y = 10
  // A vertical square in the plane x = x0 around the line.
  const auto wall = [](float x0) {
    return sbtest::quad("wall", {x0, 9.5f, -0.5f}, {x0, 10.5f, -0.5f}, {x0, 10.5f, 0.5f},
                        {x0, 9.5f, 0.5f}, true);
  };
  const glm::dvec3 from_left(-5, 10, 0), facing_right(1, 0, 0);
  s.meshes = {wall(0.4f)};  // crosses the segment at s = 0.7
  const double crossing = (double(0.4f) + 1.0) / 2.0;
  EXPECT_NEAR(ExactVisibility(s).visibility(from_left, facing_right), crossing, 1e-12);
  const auto hidden = ExactVisibility(s).hidden_intervals(from_left, facing_right);
  ASSERT_EQ(hidden.size(), 1u);
  EXPECT_NEAR(hidden[0].x, crossing, 1e-12);
  EXPECT_EQ(hidden[0].y, 1.0);
  s.meshes = {wall(-3.0f)};  // between the point and the segment
  EXPECT_EQ(ExactVisibility(s).visibility(from_left, facing_right), 0.0);
  s.meshes = {wall(3.0f)};  // beyond it
  EXPECT_EQ(ExactVisibility(s).visibility(from_left, facing_right), 1.0);
  // From the other end, looking back, the same wall at 0.4 hides s < 0.7.
  s.meshes = {wall(0.4f)};
  EXPECT_NEAR(ExactVisibility(s).visibility({5, 10, 0}, {-1, 0, 0}), 1.0 - crossing, 1e-12);
}

TEST(referenceLinearLight, HiddenIntervalsAndTheirUnion) {
  EXPECT_EQ(ExactVisibility::union_length({}), 0.0);
  // Overlapping, nested, touching and out-of-range intervals.
  EXPECT_NEAR(ExactVisibility::union_length(
                  {{0.3, 0.5}, {0.2, 0.4}, {0.7, 0.8}, {-1.0, 0.05}, {0.9, 2.0}, {0.72, 0.75}}),
              0.05 + 0.3 + 0.1 + 0.1, 1e-15);
  EXPECT_NEAR(ExactVisibility::union_length({{0.1, 0.4}, {0.4, 0.6}}), 0.5, 1e-15);
  EXPECT_EQ(ExactVisibility::union_length({{-2.0, 3.0}}), 1.0);
  // Rounding between abutting triangles' cuts leaves no sliver.
  EXPECT_EQ(ExactVisibility::union_length({{1e-16, 0.3}, {0.3 + 1e-15, 1.0 - 1e-16}}), 1.0);
  EXPECT_NEAR(ExactVisibility::union_length({{0.0, 0.3}, {0.3 + 1e-6, 1.0}}), 1.0 - 1e-6, 1e-15);
  // Two plates side by side, seen from below the segment's centre: each
  // hides the part of the segment it spans, scaled by 2 from y = 5 to y = 10.
  sb::core::Scene s;
  s.light = segment({0, 10, 0}, {1, 0, 0}, false);
  s.meshes.push_back(
      sbtest::quad("a", {-0.4f, 5, -1}, {-0.1f, 5, -1}, {-0.1f, 5, 1}, {-0.4f, 5, 1}, true));
  s.meshes.push_back(
      sbtest::quad("b", {0.2f, 5, -1}, {0.25f, 5, -1}, {0.25f, 5, 1}, {0.2f, 5, 1}, true));
  const ExactVisibility exact(s);
  // From the origin itself, as Monte Carlo's rays start there (2^-16 of
  // its coordinates, 0; it lies on no caster): x on the light = x on the
  // plate * 10 / 5.
  const double k = 2.0;
  const auto s_of = [&](double x) { return (double(float(x)) * k + 1.0) / 2.0; };
  double covered = 0.0;
  for (const glm::dvec2& i : exact.hidden_intervals({0, 0, 0}, {0, 1, 0})) {
    EXPECT_LE(i.x, i.y);
    covered += i.y - i.x;  // each plate's two triangles split its interval
  }
  const double truth = s_of(-0.1) - s_of(-0.4) + s_of(0.25) - s_of(0.2);
  EXPECT_NEAR(covered, truth, 1e-12);
  EXPECT_NEAR(exact.visibility({0, 0, 0}, {0, 1, 0}), 1.0 - truth, 1e-12);
}

// The horizon alone: a segment tilted through the tangent plane is hidden
// below it.
TEST(referenceLinearLight, TheHorizonHidesThePartBelowTheTangentPlane) {
  sb::core::Scene s;
  s.light = segment({0, 1, 0}, {0, 2, 0}, false);  // from y = -1 to y = 3
  s.meshes.push_back(
      sbtest::quad("far away", {50, 0, 50}, {51, 0, 50}, {51, 1, 50}, {50, 1, 50}, true));
  const ExactVisibility exact(s);
  // A surface at the origin facing +y, off to the side so the light is not in it.
  EXPECT_NEAR(exact.visibility({2, 0, 0}, {0, 1, 0}), 0.75, 1e-12);
  EXPECT_NEAR(exact.visibility({2, 0.5, 0}, {0, -1, 0}), 0.375, 1e-12);
  // The Monte Carlo reference applies the same rule per sample.
  const Ground g({{2, 0, 0}});
  const ref::Result r = ref::compute(s, g.positions, g.normals, {64, 1});
  EXPECT_NEAR(r.visibility.data[0], 0.75, 1.0 / 64);
}

TEST(referenceLinearLight, SegmentsAreExactAndPointsKeepTheirReason) {
  const sb::core::Scene plate = half_planes()[0].scene;
  EXPECT_EQ(ExactVisibility::unsupported_reason(plate), "");
  sb::core::Scene along_v = plate;
  along_v.light = segment({0, 10, 0}, {0, 0, 1}, true);
  EXPECT_EQ(ExactVisibility::unsupported_reason(along_v), "");
  sb::core::Scene point = plate;
  point.light.half_u = point.light.half_v = glm::vec3(0.0f);
  ASSERT_TRUE(point.light.is_point());
  const std::string why = ExactVisibility::unsupported_reason(point);
  EXPECT_EQ(why, "the light has no area (the Monte Carlo reference is exact there)");
  const Ground g({{0.5f, 0, 0}, {-2, 0, 0}});
  ref::Settings settings;
  settings.exact = true;
  const ref::Result r = ref::compute(point, g.positions, g.normals, settings);
  EXPECT_EQ(r.exact_fallback, why);
  EXPECT_EQ(r.method, "embree_stratified_packet16");
  const ref::Result seg = ref::compute(plate, g.positions, g.normals, settings);
  EXPECT_EQ(seg.exact_fallback, "");
  EXPECT_EQ(seg.method, ref::kExactMethod);
}

}  // namespace
