// The single-map techniques under the sun (one orthographic map,
// common/light_frustum.h: fit_sun_frustum), rendered through the harness's
// own stage (run/timing_contract.h) on a scene built here: a box on a
// ground and a plate floating past the ground's edge whose shadow falls on
// it. Against the analytic shadow: a ground point is shadowed exactly when
// its ray towards the sun hits the box or the plate (slab test).
//   shadow_map: V is that answer away from the shadow's edge;
//   pcf_box, pcf_jitter: V is that answer beyond its kernel's footprint of
//            the edge, and fractional only within it;
//   vsm, esm, evsm, msm, csm_convolution: that answer away from the edge;
//   pcss: across a plate's straight edge, a penumbra as wide as the sun's
//         cone makes it (the plate scene and the widths are those of
//         test_cascaded_render.cpp's PCSS test, which checks the cascades).
// These are skipped under the sun on main (they declared no sun need).
// With SB_SUN_IMAGES=<folder> set, the tests write V as PGM images.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>

#include "common/light_frustum.h"
#include "core/scene_types.h"
#include "debug_images.h"
#include "gl/context.h"
#include "plugin/registry.h"
#include "run/timing_contract.h"
#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"

namespace sb::test {
namespace {

using core::ImageF;
using core::resolve_params;
using core::Scene;
using plugin::Registry;
using plugin::TechniqueInfo;
using run::ContractStage;

constexpr int kWidth = 320;
constexpr int kHeight = 240;
constexpr int kMapSize = 1024;

struct Box {
  glm::vec3 center, half;
};
// The plate stands past the ground's edge (x 11..13 against the ground's
// 10): a fit that ignored casters outside the receivers would lose it.
const Box kBoxes[] = {{{-2.0f, 1.0f, 0.0f}, {1.0f, 1.0f, 1.0f}},
                      {{12.0f, 6.0f, 0.0f}, {1.0f, 0.05f, 1.0f}}};
const glm::vec3 kToSun = glm::normalize(glm::vec3(1.0f, 1.0f, 0.2f));

Scene sun_scene() {
  Scene s;
  s.name = "sun_single_map";
  s.meshes.push_back(make_ground_plane("ground", {0.0f, 0.0f, 0.0f}, 10.0f));
  for (size_t i = 0; i < std::size(kBoxes); ++i)
    s.meshes.push_back(make_box("box" + std::to_string(i), kBoxes[i].center, kBoxes[i].half));
  s.light = core::make_sun_light(kToSun, {0.0f, 0.0f, 0.0f}, 1e-4f, 60.0f);
  s.camera.eye = {0.0f, 14.0f, 14.0f};
  s.camera.target = {1.0f, 0.0f, 0.0f};
  s.camera.fov_y_degrees = 50.0f;
  s.camera.near_plane = 0.1f;
  s.camera.far_plane = 100.0f;
  return s;
}

bool shadowed(const glm::vec3& p) {
  for (const Box& b : kBoxes) {
    float t0 = 0.0f, t1 = 1e30f;
    for (int k = 0; k < 3; ++k) {
      const float lo = (b.center[k] - b.half[k] - p[k]) / kToSun[k];
      const float hi = (b.center[k] + b.half[k] - p[k]) / kToSun[k];
      t0 = std::max(t0, std::min(lo, hi));
      t1 = std::min(t1, std::max(lo, hi));
    }
    if (t0 <= t1) return true;
  }
  return false;
}

// The analytic V where every ground point within `margin` agrees; -1 near
// the shadow's edge.
float analytic_away_from_edges(const glm::vec3& p, float margin) {
  const bool centre = shadowed(p);
  for (int k = 0; k < 16; ++k) {
    const float a = float(k) * 0.392699f;
    if (shadowed(p + margin * glm::vec3(std::cos(a), 0.0f, std::sin(a))) != centre) return -1.0f;
  }
  return centre ? 0.0f : 1.0f;
}

// Within `margin` of where a box stands on the ground: there the map holds
// the box's bottom face (front faces are culled) at the ground's own depth,
// and what a filter reads is the culling's business, not the fit's.
bool near_contact(const glm::vec3& p, float margin) {
  for (const Box& b : kBoxes)
    if (b.center.y - b.half.y < 1e-3f && std::abs(p.x - b.center.x) < b.half.x + margin &&
        std::abs(p.z - b.center.z) < b.half.z + margin)
      return true;
  return false;
}

void maybe_write(const ImageF& img, const std::string& name) {
  write_pgm_if_asked(img, "SB_SUN_IMAGES", name);
}

// Per ground pixel: V, and the analytic answer `margin` away from edges.
struct Comparison {
  int compared = 0, in_shadow = 0, wrong = 0;    // away from edges
  int fractional = 0, fractional_near_edge = 0;  // 0.01 < V < 0.99
  std::string first_wrong;                       // where and what, for the failure message
};

class SunSingleMap : public ::testing::Test {
 protected:
  void SetUp() override {
    plugins_.load_plugins(SHADOWBENCH_PLUGIN_DIR);
    context_ = gl::create_context(gl::Backend::OSMesa);
  }
  const TechniqueInfo* find(const std::string& name) {
    const TechniqueInfo* info = plugins_.find(name);
    EXPECT_NE(info, nullptr) << name;
    return info;
  }
  ImageF render(const TechniqueInfo* info, nlohmann::json params) {
    stage_ =
        std::make_unique<ContractStage>(sun_scene(), kWidth, kHeight, std::vector{info}, plugins_);
    EXPECT_EQ(stage_->skip_reason(0), "") << info->name << " is skipped under the sun";
    params["size"] = kMapSize;
    const auto t = info->create(resolve_params(info->params, params, "", ""));
    t->prepare(stage_->inputs());
    const ImageF v = stage_->render(*t);
    maybe_write(v, info->name);
    return v;
  }
  // `margin`: world units on the ground; `tolerance`: |V − analytic| that counts as wrong.
  Comparison compare(const ImageF& v, float margin, float tolerance) const {
    const ImageF position = stage_->read_gbuffer()[0];
    const ImageF normal = stage_->read_gbuffer()[1];
    Comparison c;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        if (position.at(x, y, 3) == 0.0f || normal.at(x, y, 1) < 0.99f) continue;
        const glm::vec3 p{position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2)};
        if (std::abs(p.y) > 1e-3f) continue;  // box tops
        if (near_contact(p, margin)) continue;
        const float expected = analytic_away_from_edges(p, margin);
        const float got = v.at(x, y);
        const auto note = [&] {
          if (c.first_wrong.empty())
            c.first_wrong = "V " + std::to_string(got) + " at (" + std::to_string(p.x) + ", " +
                            std::to_string(p.z) + "), analytic " + std::to_string(expected);
        };
        if (got > 0.01f && got < 0.99f) {
          ++c.fractional;
          c.fractional_near_edge += expected < 0.0f;
          if (expected >= 0.0f) note();
        }
        if (expected < 0.0f) continue;
        ++c.compared;
        c.in_shadow += expected == 0.0f;
        if (std::abs(got - expected) > tolerance) {
          ++c.wrong;
          note();
        }
      }
    return c;
  }
  // One map texel on the ground: the texel across the light, stretched by
  // the ground's slant to it.
  static float ground_texel() {
    return techniques::fit_sun_frustum(sun_scene()).texel_world(kMapSize) / kToSun.y;
  }

  Registry plugins_;
  std::unique_ptr<gl::Context> context_;
  std::unique_ptr<ContractStage> stage_;
};

TEST_F(SunSingleMap, HardMapMatchesTheCastersProjectionAlongTheSun) {
  const ImageF v = render(find("shadow_map"), nlohmann::json::object());
  // A few texels: the map's sampling and its bias.
  const Comparison c = compare(v, 4.0f * ground_texel(), 0.5f);
  EXPECT_GT(c.compared, 20000);
  EXPECT_GT(c.in_shadow, 500);
  EXPECT_EQ(c.wrong, 0) << "of " << c.compared << "; " << c.first_wrong;
  EXPECT_EQ(c.fractional, 0);
}

// The plate past the ground's edge shadows the ground at x 5..7: that
// shadow is in the map only if the fit holds the plate.
TEST_F(SunSingleMap, ACasterPastTheGroundStillShadowsIt) {
  const ImageF v = render(find("shadow_map"), nlohmann::json::object());
  const ImageF position = stage_->read_gbuffer()[0];
  int under_plate = 0, dark = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const glm::vec3 p{position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2)};
      if (position.at(x, y, 3) == 0.0f || std::abs(p.y) > 1e-3f || p.x < 4.0f) continue;
      if (analytic_away_from_edges(p, 0.2f) != 0.0f) continue;
      ++under_plate;
      dark += v.at(x, y) < 0.5f;
    }
  EXPECT_GT(under_plate, 200);
  EXPECT_EQ(dark, under_plate);
}

// A k×k box kernel reaches (k−1)/2 texels either way: V is exact beyond
// that footprint (plus a texel for the map's sampling and bias) and
// fractional only inside it.
TEST_F(SunSingleMap, PcfPenumbraStaysInsideTheKernelsFootprint) {
  const int k = 7;
  const ImageF v = render(find("pcf_box"), {{"k", k}});
  const float footprint = (0.5f * float(k - 1) + 1.5f) * ground_texel();
  const Comparison c = compare(v, footprint, 0.01f);
  EXPECT_GT(c.compared, 20000);
  EXPECT_GT(c.in_shadow, 500);
  EXPECT_EQ(c.wrong, 0) << "of " << c.compared << "; " << c.first_wrong;
  EXPECT_GT(c.fractional, 100);  // it filters
  EXPECT_EQ(c.fractional_near_edge, c.fractional) << c.first_wrong;
}

// pcf_jitter's taps lie on a disk of radius_texels (default 4.5): V is exact
// beyond it (plus a texel and a half, as above), its early-out included, and
// fractional only inside it.
TEST_F(SunSingleMap, JitteredPcfPenumbraStaysInsideItsDisk) {
  const ImageF v = render(find("pcf_jitter"), nlohmann::json::object());
  const Comparison c = compare(v, (4.5f + 1.5f) * ground_texel(), 0.01f);
  EXPECT_GT(c.compared, 20000);
  EXPECT_GT(c.in_shadow, 500);
  EXPECT_EQ(c.wrong, 0) << "of " << c.compared << "; " << c.first_wrong;
  EXPECT_GT(c.fractional, 100);
  EXPECT_EQ(c.fractional_near_edge, c.fractional) << c.first_wrong;
}

// The filtered maps store a depth linear in distance along the light
// (depth01 of an orthographic map's view depth): with one caster over each
// receiver they reconstruct the hard answer away from edges.
TEST_F(SunSingleMap, FilteredMapsMatchTheHardShadowAwayFromEdges) {
  for (const char* name : {"vsm", "esm", "evsm", "msm", "csm_convolution"}) {
    const ImageF v = render(find(name), nlohmann::json::object());
    const Comparison c = compare(v, 6.0f * ground_texel(), 0.1f);
    EXPECT_GT(c.in_shadow, 500) << name;
    EXPECT_LE(c.wrong, c.compared / 200)
        << name << ": " << c.wrong << " of " << c.compared << "; " << c.first_wrong;
  }
}

// Every sun-capable single map keeps the timing contract under a turning
// sun: the fit is made in render(), so a frame after the sun turned equals
// one prepared under it, and the frames are deterministic.
TEST_F(SunSingleMap, KeepTheTimingContractUnderATurningSun) {
  for (const char* name : {"shadow_map", "pcf_gauss", "pcss", "vsm", "msm"}) {
    const TechniqueInfo* info = find(name);
    stage_ = std::make_unique<ContractStage>(sun_scene(), 96, 72, std::vector{info}, plugins_);
    ASSERT_EQ(stage_->skip_reason(0), "") << name;
    const core::Params p = resolve_params(info->params, {{"size", 256}}, "", "");
    const auto create = [&] { return info->create(p); };
    const core::AreaLight first = stage_->scene().light;
    // The sun turned by about 10 degrees.
    const core::AreaLight second =
        core::make_sun_light(glm::normalize(kToSun + glm::vec3(-0.2f, 0.0f, 0.1f)), first.target,
                             first.angular_diameter, 60.0f);
    const ContractStage::Frames f = stage_->across_a_move(
        create, [&] { stage_->set_light(first); }, [&] { stage_->set_light(second); });
    stage_->set_light(first);
    EXPECT_EQ(run::differing_pixels(f.a_moved, f.b_moved), 0u)
        << name << ": a frame after the sun turned differs from one prepared under it";
    EXPECT_GT(run::differing_pixels(f.a_first, f.a_moved), 0u)
        << name << ": turning the sun changed nothing";
    for (const run::ContractCheck& c : {run::check_visibility_written(*stage_, create),
                                        run::check_deterministic(*stage_, create)})
      EXPECT_TRUE(c.passed()) << name << ": " << c.name << ": " << c.failure;
  }
}

// A plate 2 units over a small ground, its straight edge at x = 0, under a
// sun almost overhead of angular diameter `alpha`.
constexpr float kPlateHeight = 2.0f;
Scene plate_scene(float alpha) {
  Scene s;
  s.name = "sun_plate";
  s.meshes.push_back(make_ground_plane("ground", {0.0f, 0.0f, -1.0f}, 6.0f));
  s.meshes.push_back(make_box("plate", {-2.0f, kPlateHeight, -1.0f}, {2.0f, 0.02f, 3.0f}));
  s.light = core::make_sun_light({0.0f, 1.0f, 0.05f}, {0.0f, 0.0f, -1.0f}, alpha, 80.0f);
  s.camera.eye = {0.3f, 1.0f, 5.0f};
  s.camera.target = {0.0f, 0.0f, -1.0f};
  s.camera.fov_y_degrees = 50.0f;
  s.camera.near_plane = 0.1f;
  s.camera.far_plane = 100.0f;
  return s;
}

// The exact penumbra's 10-90 % width across a straight edge at height h
// under a disk of angular diameter alpha: the disk's radius on the plane
// perpendicular to the sun is R = h·tan(alpha/2), and the occluded fraction
// at offset u·R from the edge's shadow is (acos(u) − u·sqrt(1 − u²))/π,
// 0.1 at u = ±u10.
double exact_penumbra_width(double h, double alpha) {
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 60; ++i) {
    const double u = 0.5 * (lo + hi);
    ((std::acos(u) - u * std::sqrt(1.0 - u * u)) / 3.14159265358979 > 0.1 ? lo : hi) = u;
  }
  return 2.0 * lo * h * std::tan(0.5 * alpha);
}

// Where V first reaches `level` along the ground row through z ≈ -1.1 that
// crosses x = 0 (interpolated between pixels), x increasing.
float crossing(const ImageF& position, const ImageF& v, float level) {
  int best_row = -1;
  float best = 1e30f;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x + 1 < kWidth; ++x)
      if (position.at(x, y, 3) != 0.0f && position.at(x, y, 0) <= 0.0f &&
          position.at(x + 1, y, 0) > 0.0f && std::abs(position.at(x, y, 1)) < 1e-3f &&
          std::abs(position.at(x, y, 2) + 1.1f) < best) {
        best = std::abs(position.at(x, y, 2) + 1.1f);
        best_row = y;
      }
  if (best_row < 0) return 1e30f;
  for (int x = 0; x + 1 < kWidth; ++x) {
    const float a = v.at(x, best_row), b = v.at(x + 1, best_row);
    if (position.at(x, best_row, 0) > -1.0f && a < level && b >= level) {
      const float w = (level - a) / (b - a);
      return (1.0f - w) * position.at(x, best_row, 0) + w * position.at(x + 1, best_row, 0);
    }
  }
  return 1e30f;
}

// PCSS filters the hard edge with a box as wide as the penumbra it
// predicts, w = (d_r − d_b)·2·tan(alpha/2) = 2h·tan(alpha/2) here, whose
// 10-90 % ramp is 0.8·w: within 20 % of that; the exact disk's ramp is
// 0.69·w, checked loosely. The edge is centred on the hard shadow's, and
// the penumbra is twice as wide under a sun twice as large.
TEST_F(SunSingleMap, PcssPenumbraGrowsWithTheSunsAngularSize) {
  const TechniqueInfo* info = find("pcss");
  double widths[2];
  for (int k = 0; k < 2; ++k) {
    const float alpha = k == 0 ? 0.2f : 0.1f;
    stage_ = std::make_unique<ContractStage>(plate_scene(alpha), kWidth, kHeight, std::vector{info},
                                             plugins_);
    ASSERT_EQ(stage_->skip_reason(0), "") << "pcss is skipped under the sun";
    const auto t = info->create(resolve_params(
        info->params, {{"size", kMapSize}, {"filter_taps", 9}, {"search_taps", 7}}, "", ""));
    t->prepare(stage_->inputs());
    const ImageF v = stage_->render(*t);
    maybe_write(v, k == 0 ? "pcss_plate_wide_sun" : "pcss_plate_narrow_sun");
    const ImageF position = stage_->read_gbuffer()[0];
    const float x10 = crossing(position, v, 0.1f), x50 = crossing(position, v, 0.5f),
                x90 = crossing(position, v, 0.9f);
    const double exact = exact_penumbra_width(kPlateHeight, alpha);
    widths[k] = double(x90 - x10);
    SCOPED_TRACE("alpha " + std::to_string(alpha) + ": 10-90 % from " + std::to_string(x10) +
                 " to " + std::to_string(x90) + ", exact width " + std::to_string(exact));
    const double box_ramp = 0.8 * 2.0 * kPlateHeight * std::tan(0.5 * alpha);
    EXPECT_GT(widths[k], 0.85 * box_ramp);
    EXPECT_LT(widths[k], 1.2 * box_ramp);
    EXPECT_GT(widths[k], 0.8 * exact);
    EXPECT_LT(widths[k], 1.6 * exact);
    EXPECT_LT(std::abs(x50), 0.5 * exact);
  }
  std::printf("pcss 10-90 %% widths: %.4f (alpha 0.2), %.4f (alpha 0.1)\n", widths[0], widths[1]);
  EXPECT_NEAR(widths[0] / widths[1], 2.0, 0.4);
}

}  // namespace
}  // namespace sb::test
