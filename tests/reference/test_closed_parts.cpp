// Closed casters made of several parts (triangles connected through shared
// edges), wound either way: the exact reference and the adaptive
// reference's two proofs against the dense uniform Monte Carlo reference,
// whose rays are blocked by any triangle whichever way it winds. One mesh
// each, as merged glTF exports come: two cubes, the smaller wound inward;
// a room wound inward (seen from inside) around a cube and a hollow box
// (its cavity wound inward); a box with another resting on it (touching
// face to face) and a third pushed into it, both wound inward; and
// hand-made points inside one part behind another, and inside a part that
// the light pokes out of.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "reference/exact_visibility.h"
#include "reference/reference.h"
#include "scenes/mesh_builders.h"
#include "test_scenes.h"

namespace {

namespace ref = sb::reference;
using ref::Result;
using ref::Settings;

constexpr int kPartsWidth = 160, kPartsHeight = 120;
constexpr int kPartsSpp = 256;

// The same faces wound the other way.
sb::core::Mesh inverted(sb::core::Mesh m) {
  for (size_t i = 0; i + 2 < m.indices.size(); i += 3)
    std::swap(m.indices[i + 1], m.indices[i + 2]);
  return m;
}

// The parts as one mesh.
sb::core::Mesh merged(const std::string& name, const std::vector<sb::core::Mesh>& parts) {
  sb::core::Mesh out;
  out.name = name;
  for (const sb::core::Mesh& m : parts) {
    const auto base = uint32_t(out.positions.size());
    out.positions.insert(out.positions.end(), m.positions.begin(), m.positions.end());
    for (const uint32_t i : m.indices) out.indices.push_back(base + i);
  }
  return out;
}

sb::core::Scene lit_from_above(sb::core::Mesh caster) {
  return sbtest::over_plane(std::move(caster));
}

// Two cubes over the ground, the smaller wound inward: the mesh's total
// signed volume is the larger one's, positive.
sb::core::Scene two_cubes_one_inverted() {
  return lit_from_above(
      merged("cubes", {sb::make_box("big", {-1.0f, 1.4f, 0.0f}, glm::vec3(0.5f)),
                       inverted(sb::make_box("small", {0.9f, 1.2f, 0.3f}, glm::vec3(0.3f)))}));
}

// A closed room wound inward, so that its walls face the camera and the
// light inside it, around an outward cube on its floor and a floating
// hollow box whose cavity is wound inward (as a solid with a cavity is):
// the room's negative volume outweighs the rest.
sb::core::Scene room_around_a_cube_and_a_hollow_box() {
  sb::core::Scene s;
  s.meshes.push_back(
      merged("room", {inverted(sb::make_box("walls", {0, 3, 0}, {4, 3, 4})),
                      sb::make_box("cube", {0.8f, 0.5f, 0.2f}, glm::vec3(0.5f)),
                      sb::make_box("hollow", {-1.4f, 2.0f, -0.6f}, glm::vec3(0.7f)),
                      inverted(sb::make_box("cavity", {-1.4f, 2.0f, -0.6f}, glm::vec3(0.4f)))}));
  s.light.center = {0.3f, 5.0f, 0.2f};
  s.light.half_u = {0.9f, 0, 0};
  s.light.half_v = {0, 0, 0.9f};
  s.camera.eye = {0, 5.5f, 3.8f};
  s.camera.target = {0, 0, -0.5f};
  s.camera.fov_y_degrees = 70.0f;
  return s;
}

// A floating box with a smaller one resting on it, face to face without
// sharing an edge, and a third pushed halfway into its side, both wound
// inward.
sb::core::Scene touching_and_interpenetrating_boxes() {
  return lit_from_above(merged(
      "stack", {sb::make_box("base", {0.0f, 0.9f, 0.0f}, {0.8f, 0.3f, 0.6f}),
                inverted(sb::make_box("on_top", {0.2f, 1.5f, 0.1f}, glm::vec3(0.3f))),
                inverted(sb::make_box("pushed_in", {0.8f, 0.9f, -0.3f}, glm::vec3(0.25f)))}));
}

bool is_covered(const ref::GBuffer& g, size_t i) { return g.positions.data[i * 4 + 3] > 0.5f; }

// The exact reference against 256-spp Monte Carlo, as test_exact_agreement.cpp
// compares them (4 standard errors, one sample's weight where the stated
// error is 0, on all but 0.1% of the covered pixels), and no pixel off by
// more than 0.25, several times what 256 samples can stray.
void expect_exact_agrees(const sb::core::Scene& scene, const std::string& label) {
  const ref::GBuffer g = ref::trace_gbuffer(scene, kPartsWidth, kPartsHeight);
  Settings exact_settings;
  exact_settings.exact = true;
  const Result exact = ref::compute(scene, g.positions, g.normals, exact_settings);
  ASSERT_EQ(exact.method, ref::kExactMethod) << exact.exact_fallback;
  const Result mc = ref::compute(scene, g.positions, g.normals, {kPartsSpp, 1});
  size_t covered_px = 0, outside = 0, far_off = 0, penumbra = 0;
  double worst = 0.0;
  for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
    if (!is_covered(g, i)) continue;
    ++covered_px;
    const double e = exact.visibility.data[i], m = mc.visibility.data[i];
    const double d = std::abs(e - m);
    penumbra += m > 0.0 && m < 1.0;
    worst = std::max(worst, d);
    outside += d > 4.0 * std::max(double(mc.std_error.data[i]), 1.0 / kPartsSpp);
    far_off += d > 0.25;
  }
  std::printf(
      "%s: %zu covered px (%zu in the Monte Carlo penumbra), %zu beyond 4 sigma, %zu off "
      "by more than 0.25, max |diff| %.4f\n",
      label.c_str(), covered_px, penumbra, outside, far_off, worst);
  EXPECT_GT(penumbra, 500u) << label << ": too little penumbra to test anything";
  EXPECT_LE(double(outside), 0.001 * double(covered_px)) << label;
  EXPECT_EQ(far_off, 0u) << label;
}

// The adaptive reference from a 4-sample pilot against the uniform one at
// its full count. Where the casters have an exact form, an agreeing pilot
// stops only when proven: lit by sees_whole_light, occluded by
// hides_whole_light. Every pixel that stopped there with V = 1 or V = 0 must
// have the full count's very value; both proofs must have stopped many.
void expect_proofs_hold(const sb::core::Scene& scene, const std::string& label) {
  const ref::GBuffer g = ref::trace_gbuffer(scene, kPartsWidth, kPartsHeight);
  const Result full = ref::compute(scene, g.positions, g.normals, {kPartsSpp, 1});
  Settings s(kPartsSpp, 1);
  s.adaptive = true;
  s.pilot_spp = 4;
  s.target_std_error = 0.02;
  const Result a = ref::compute(scene, g.positions, g.normals, s);
  ASSERT_EQ(a.method, ref::kAdaptiveMethod);
  size_t proven_lit = 0, proven_occluded = 0, wrong_lit = 0, wrong_occluded = 0, beyond = 0;
  double worst_occluded = 0.0;
  for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
    if (!is_covered(g, i)) continue;
    const float av = a.visibility.data[i], fv = full.visibility.data[i];
    const double sa = a.std_error.data[i], sf = full.std_error.data[i];
    beyond += std::abs(double(av) - double(fv)) >
              4.0 * std::max(std::sqrt(sa * sa + sf * sf), 1.0 / kPartsSpp);
    if (a.samples.data[i] != 4.0f) continue;
    if (av == 1.0f) {
      ++proven_lit;
      wrong_lit += fv != 1.0f;
    } else if (av == 0.0f) {
      ++proven_occluded;
      wrong_occluded += fv != 0.0f;
      worst_occluded = std::max(worst_occluded, double(fv));
    }
  }
  std::printf(
      "%s: pilots proven lit %zu (%zu wrong), proven occluded %zu (%zu wrong, full count "
      "up to %.3f there); %zu px beyond 4 sigma of the full count\n",
      label.c_str(), proven_lit, wrong_lit, proven_occluded, wrong_occluded, worst_occluded,
      beyond);
  EXPECT_GT(proven_lit, 1000u) << label;
  EXPECT_GT(proven_occluded, 50u) << label;
  EXPECT_EQ(wrong_lit, 0u) << label;
  EXPECT_EQ(wrong_occluded, 0u) << label;
  EXPECT_EQ(beyond, 0u) << label;
}

TEST(ReferenceClosedParts, ExactAgreesWithMonteCarloOnPartsWoundBothWays) {
  expect_exact_agrees(two_cubes_one_inverted(), "two cubes, one inverted");
}

// The same under a linear light (the square's u side), whose exact form
// (hidden intervals) applies the same rule.
TEST(ReferenceClosedParts, ExactAgreesWithMonteCarloOnPartsWoundBothWaysUnderASegment) {
  sb::core::Scene scene = two_cubes_one_inverted();
  scene.light.half_v = {0, 0, 0};
  expect_exact_agrees(scene, "two cubes, one inverted, segment light");
}

TEST(ReferenceClosedParts, ExactAgreesWithMonteCarloOnNestedShells) {
  expect_exact_agrees(room_around_a_cube_and_a_hollow_box(), "room, cube, hollow box");
}

TEST(ReferenceClosedParts, ExactAgreesWithMonteCarloOnTouchingParts) {
  expect_exact_agrees(touching_and_interpenetrating_boxes(), "touching boxes");
}

TEST(ReferenceClosedParts, AdaptiveProofsHoldOnPartsWoundBothWays) {
  expect_proofs_hold(two_cubes_one_inverted(), "two cubes, one inverted");
}

TEST(ReferenceClosedParts, AdaptiveProofsHoldOnNestedShells) {
  expect_proofs_hold(room_around_a_cube_and_a_hollow_box(), "room, cube, hollow box");
}

TEST(ReferenceClosedParts, AdaptiveProofsHoldOnTouchingParts) {
  expect_proofs_hold(touching_and_interpenetrating_boxes(), "touching boxes");
}

// Keeping only each closed part's triangles that face the point, with the
// inside test, against keeping every triangle of the same mesh (no culling,
// no inside test: right wherever the point is outside every part), on
// random points of the ground or the room's floor, beside and under the
// parts.
TEST(ReferenceClosedParts, KeepingTheSidesThatFaceThePointChangesNothing) {
  const std::pair<std::string, sb::core::Scene> scenes[] = {
      {"two cubes, one inverted", two_cubes_one_inverted()},
      {"room, cube, hollow box", room_around_a_cube_and_a_hollow_box()},
      {"touching boxes", touching_and_interpenetrating_boxes()}};
  for (const auto& [label, scene] : scenes) {
    SCOPED_TRACE(label);
    std::vector<bool> closed, open(scene.meshes.size(), false);
    for (const sb::core::Mesh& m : scene.meshes) closed.push_back(m.casts_shadow);
    const ref::ExactVisibility culled(scene, closed), all(scene, open);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> xz(-2.5, 2.5);
    int soft = 0;
    for (int i = 0; i < 400; ++i) {
      const glm::dvec3 p(xz(rng), 0.0, xz(rng)), up(0, 1, 0);
      const double v = all.visibility(p, up);
      soft += v > 0.0 && v < 1.0;
      EXPECT_NEAR(culled.visibility(p, up), v, 1e-7) << "at " << p.x << ", " << p.z;
    }
    EXPECT_GT(soft, 20);
  }
}

// Points inside a box, under a small box inside it (the same mesh, both
// wound outward): every shadow ray leaves the large box, so Monte Carlo
// gives V = 0, though the segment to the light's centre first enters the
// small box. (A silhouette pixel that lands on a back face, or a point of
// one part inside another, starts its rays inside a solid like this.)
TEST(ReferenceClosedParts, APointInsideOnePartBehindAnotherIsInItsUmbra) {
  sb::core::Scene scene;
  scene.light = sbtest::square_light();
  scene.meshes.push_back(merged("nested", {sb::make_box("large", {0, 2, 0}, {1.5f, 1.0f, 1.5f}),
                                           sb::make_box("small", {0, 2.8f, 0}, glm::vec3(0.05f))}));
  std::vector<glm::vec3> points;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j) points.push_back({0.04f * float(i), 1.8f, 0.05f * float(j)});
  sb::core::ImageF positions(int(points.size()), 1, 4, 1.0f),
      normals(int(points.size()), 1, 3, 0.0f);
  for (size_t i = 0; i < points.size(); ++i) {
    for (int c = 0; c < 3; ++c) positions.data[i * 4 + size_t(c)] = points[i][c];
    normals.data[i * 3 + 1] = 1.0f;  // up, towards the light
  }
  Settings exact_settings;
  exact_settings.exact = true;
  const Result exact = ref::compute(scene, positions, normals, exact_settings);
  const Result mc = ref::compute(scene, positions, normals, {kPartsSpp, 1});
  const ref::ExactVisibility proofs(scene, {true});
  for (size_t i = 0; i < points.size(); ++i) {
    SCOPED_TRACE("point " + std::to_string(i));
    EXPECT_EQ(mc.visibility.data[i], 0.0f);
    EXPECT_EQ(exact.visibility.data[i], 0.0f);
    const glm::dvec3 surface(points[i]), up(0, 1, 0);
    EXPECT_TRUE(proofs.hides_whole_light(surface, surface + 1e-4 * up, up));
  }
}

// A closed box around the point that the light pokes out of (its side
// x = 0.2 cuts the light, which spans x in [-1, 1]): rays to the light's
// part inside the box meet nothing, rays to the rest cross that side, so
// V = 0.6 exactly. The box winds around the point as often as around the
// light's centre, yet keeping only the sides that face the point (none,
// from inside) would read V = 1: a part the light touches keeps every
// triangle.
TEST(ReferenceClosedParts, APartTheLightPokesOutOfKeepsEveryTriangle) {
  sb::core::Scene scene;
  scene.light = sbtest::square_light();
  scene.meshes.push_back(sb::make_box("housing", {-1.4f, 5.5f, 0}, {1.6f, 6.5f, 3.0f}));
  const std::vector<glm::vec3> points{
      {-0.9f, 0, 0.3f}, {-0.7f, 0, 0.3f}, {-0.5f, 0, 0.3f}, {-0.3f, 0, 0.3f}, {-0.1f, 0, 0.3f}};
  sb::core::ImageF positions(int(points.size()), 1, 4, 1.0f),
      normals(int(points.size()), 1, 3, 0.0f);
  for (size_t i = 0; i < points.size(); ++i) {
    for (int c = 0; c < 3; ++c) positions.data[i * 4 + size_t(c)] = points[i][c];
    normals.data[i * 3 + 1] = 1.0f;
  }
  Settings exact_settings;
  exact_settings.exact = true;
  const Result exact = ref::compute(scene, positions, normals, exact_settings);
  const Result mc = ref::compute(scene, positions, normals, {1024, 1});
  for (size_t i = 0; i < points.size(); ++i) {
    SCOPED_TRACE("point " + std::to_string(i));
    EXPECT_NEAR(exact.visibility.data[i], 0.6, 1e-6);
    EXPECT_NEAR(mc.visibility.data[i], 0.6,
                4.0 * std::max(double(mc.std_error.data[i]), 1.0 / 1024));
  }
}

}  // namespace
