// cascaded_shadow_map rendered on a small sun scene built here (boxes over a
// ground, from near the camera to far away, under a sun of tiny angular
// size), through the harness's own stage (run/timing_contract.h: G-buffer,
// needs and frames as the runner draws them), against the analytic shadow:
// a ground point is in shadow exactly when its ray towards the sun hits a
// box. Also the seams between cascades, the timing contract under the sun,
// and the technique's GPU memory (drives Mesa).
//
// With SB_CSM_IMAGES=<folder> set, the tests write what they render there as
// PGM images (V, and the cascade index) for a person to look at.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>

#include "core/scene_types.h"
#include "debug_images.h"
#include "gl/allocation_meter.h"
#include "gl/context.h"
#include "plugin/registry.h"
#include "run/timing_contract.h"
#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"

namespace sb::test {
namespace {

using core::ImageF;
using core::Params;
using core::resolve_params;
using core::Scene;
using plugin::Registry;
using plugin::TechniqueInfo;
using run::ContractStage;

constexpr int kWidth = 320;
constexpr int kHeight = 240;

struct Box {
  glm::vec3 center, half;
};
// From 5 units in front of the camera to 40 away: their shadows fall in
// every cascade.
const Box kBoxes[] = {{{-1.0f, 0.6f, 3.0f}, {0.5f, 0.6f, 0.5f}},
                      {{1.5f, 1.0f, -3.0f}, {0.7f, 1.0f, 0.7f}},
                      {{-2.5f, 1.5f, -12.0f}, {1.0f, 1.5f, 1.0f}},
                      {{3.0f, 2.0f, -24.0f}, {1.4f, 2.0f, 1.4f}},
                      {{-4.0f, 2.5f, -34.0f}, {1.8f, 2.5f, 1.8f}}};
const glm::vec3 kToSun = glm::normalize(glm::vec3(0.9f, 0.8f, 0.3f));

Scene sun_scene(float angular_diameter) {
  Scene s;
  s.name = "cascaded_boxes";
  s.meshes.push_back(make_ground_plane("ground", {0.0f, 0.0f, -15.0f}, 30.0f));
  for (size_t i = 0; i < std::size(kBoxes); ++i)
    s.meshes.push_back(make_box("box" + std::to_string(i), kBoxes[i].center, kBoxes[i].half));
  s.light = core::make_sun_light(kToSun, {0.0f, 0.0f, -15.0f}, angular_diameter, 80.0f);
  s.camera.eye = {0.0f, 4.0f, 9.0f};
  s.camera.target = {0.0f, 0.0f, -20.0f};
  s.camera.fov_y_degrees = 50.0f;
  s.camera.near_plane = 0.1f;
  s.camera.far_plane = 200.0f;
  return s;
}

// Does the ray from p towards the sun hit a box (slab test)?
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

// The analytic answer where all points within `margin` on the ground agree
// (away from the shadow's edge); -1 elsewhere.
float analytic_away_from_edges(const glm::vec3& p, float margin) {
  const bool centre = shadowed(p);
  for (int k = 0; k < 8; ++k) {
    const float a = float(k) * 0.785398f;
    if (shadowed(p + margin * glm::vec3(std::cos(a), 0.0f, std::sin(a))) != centre) return -1.0f;
  }
  return centre ? 0.0f : 1.0f;
}

void maybe_write(const ImageF& img, const std::string& name) {
  write_pgm_if_asked(img, "SB_CSM_IMAGES", name);
}

class CascadedRender : public ::testing::Test {
 protected:
  void SetUp() override {
    plugins_.load_plugins(SHADOWBENCH_PLUGIN_DIR);
    context_ = gl::create_context(gl::Backend::OSMesa);
    info_ = plugins_.find("cascaded_shadow_map");
    ASSERT_NE(info_, nullptr);
  }
  void stage_for(float angular_diameter) {
    stage_ = std::make_unique<ContractStage>(sun_scene(angular_diameter), kWidth, kHeight,
                                             std::vector{info_}, plugins_);
    ASSERT_EQ(stage_->skip_reason(0), "");
  }
  Params params(nlohmann::json p) const {
    if (!p.contains("size")) p["size"] = 1024;
    return resolve_params(info_->params, p, "", "");
  }
  ImageF render(const nlohmann::json& p) {
    const auto t = info_->create(params(p));
    t->prepare(stage_->inputs());
    return stage_->render(*t);
  }

  Registry plugins_;
  std::unique_ptr<gl::Context> context_;
  const TechniqueInfo* info_ = nullptr;
  std::unique_ptr<ContractStage> stage_;
};

TEST_F(CascadedRender, IsSkippedUnderALocalLight) {
  ContractStage local(run::contract_scene(), 64, 48, std::vector{info_}, plugins_);
  EXPECT_NE(local.skip_reason(0), "");
}

// Hard lookups match the analytic shadow on ground pixels away from its
// edge, in every cascade: the far pixels are right only if each pixel is
// looked up in its own cascade (cascade 0's box does not reach them).
TEST_F(CascadedRender, HardShadowsMatchTheBoxesProjectionAlongTheSunInEveryCascade) {
  stage_for(1e-4f);
  const ImageF v = render({{"filter", "hard"}});
  const ImageF cascade = render({{"filter", "hard"}, {"output", "cascade"}, {"blend_band", 0.0}});
  maybe_write(v, "hard_v");
  maybe_write(cascade, "hard_cascade");
  const ImageF position = stage_->read_gbuffer()[0];
  const ImageF normal = stage_->read_gbuffer()[1];
  // Per cascade (0..3): ground pixels compared, shadowed ones among them, mismatches.
  int compared[4] = {}, in_shadow[4] = {}, wrong[4] = {};
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (position.at(x, y, 3) == 0.0f || normal.at(x, y, 1) < 0.99f) continue;
      const glm::vec3 p{position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2)};
      if (std::abs(p.y) > 1e-3f) continue;  // box tops
      const float expected = analytic_away_from_edges(p, 0.25f);
      if (expected < 0.0f) continue;
      const int c = std::clamp(int(std::lround(cascade.at(x, y) * 3.0f)), 0, 3);
      ++compared[c];
      in_shadow[c] += expected == 0.0f;
      wrong[c] += std::abs(v.at(x, y) - expected) > 0.5f;
    }
  for (int c = 0; c < 4; ++c) {
    EXPECT_GT(compared[c], 200) << "cascade " << c;
    EXPECT_GT(in_shadow[c], 20) << "cascade " << c;
    EXPECT_LE(wrong[c], compared[c] / 200) << "cascade " << c << ": " << wrong[c] << " of "
                                           << compared[c] << " (" << in_shadow[c] << " in shadow)";
  }
}

// A long bar along the view, its soft shadow a strip on the ground running
// from near the camera to far away, across every cascade boundary.
Scene bar_scene() {
  Scene s;
  s.name = "cascaded_bar";
  s.meshes.push_back(make_ground_plane("ground", {0.0f, 0.0f, -15.0f}, 30.0f));
  s.meshes.push_back(make_box("bar", {0.0f, 1.5f, -16.0f}, {0.3f, 0.1f, 25.0f}));
  s.light = core::make_sun_light({1.0f, 1.2f, 0.0f}, {0.0f, 0.0f, -15.0f}, 1e-4f, 80.0f);
  s.camera.eye = {0.5f, 3.0f, 9.0f};
  s.camera.target = {-1.0f, 0.0f, -30.0f};
  s.camera.fov_y_degrees = 50.0f;
  s.camera.near_plane = 0.1f;
  s.camera.far_plane = 200.0f;
  return s;
}
constexpr float kBarShadowLeft = -0.3f - 1.6f / 1.2f;  // the strip's far edge from the bar (x)
constexpr float kLineEnd = -35.0f;  // z: short of the bar's end, where its shadow ends

// V along the ground line x = x0, one sample per image row that sees it
// (interpolated between the two pixels whose ground points bracket x0),
// from the bottom of the image (near) up; with the cascade index there.
struct LineSample {
  float v, cascade;
};
std::vector<LineSample> along_line(const ImageF& position, const ImageF& v, const ImageF& cascade,
                                   float x0) {
  std::vector<LineSample> out;
  for (int y = kHeight - 1; y >= 0; --y)
    for (int x = 0; x + 1 < kWidth; ++x) {
      if (position.at(x, y, 3) == 0.0f || position.at(x + 1, y, 3) == 0.0f) continue;
      if (std::abs(position.at(x, y, 1)) > 1e-3f || std::abs(position.at(x + 1, y, 1)) > 1e-3f)
        continue;  // the ground only
      const float a = position.at(x, y, 0), b = position.at(x + 1, y, 0);
      if ((a - x0) * (b - x0) > 0.0f || a == b) continue;
      if (position.at(x, y, 2) < kLineEnd) return out;
      const float w = (x0 - a) / (b - a);
      out.push_back({(1.0f - w) * v.at(x, y) + w * v.at(x + 1, y),
                     (1.0f - w) * cascade.at(x, y) + w * cascade.at(x + 1, y)});
      break;
    }
  return out;
}

// The largest change of V between successive samples, and whether the
// samples cross every boundary (cascade 0 to the last).
float largest_step(const std::vector<LineSample>& line) {
  float step = 0.0f;
  for (size_t i = 1; i < line.size(); ++i)
    step = std::max(step, std::abs(line[i].v - line[i - 1].v));
  return step;
}

// A coarse PCF (7×7 taps, 128² per cascade) blurs the strip's edge over a
// few texels: a band of world width that grows from cascade to cascade. On a
// ground line just outside the edge, V is therefore a step function of the
// cascade with hard seams, and the blend band spreads each step over many
// rows. The line also crosses every boundary only if each pixel is looked up
// in the cascade of its depth.
TEST_F(CascadedRender, BlendBandsLeaveNoJumpAtTheSeams) {
  stage_ =
      std::make_unique<ContractStage>(bar_scene(), kWidth, kHeight, std::vector{info_}, plugins_);
  const nlohmann::json soft = {{"filter", "pcf"}, {"filter_taps", 7}, {"size", 128}};
  const auto with = [&](float band, bool show) {
    nlohmann::json p = soft;
    p["blend_band"] = band;
    if (show) p["output"] = "cascade";
    return render(p);
  };
  const ImageF v_blended = with(0.3f, false), v_hard = with(0.0f, false);
  const ImageF c_blended = with(0.3f, true), c_hard = with(0.0f, true);
  maybe_write(v_blended, "seam_blended_v");
  maybe_write(v_hard, "seam_hard_v");
  maybe_write(c_blended, "seam_cascade");
  const ImageF position = stage_->read_gbuffer()[0];
  const float x0 = kBarShadowLeft - 0.2f;
  const auto blended = along_line(position, v_blended, c_blended, x0);
  const auto hard = along_line(position, v_hard, c_hard, x0);
  ASSERT_GT(blended.size(), size_t(kHeight / 2));
  EXPECT_LT(blended.front().cascade, 1.0f / 3.0f);  // cascade 0 (or its band)
  EXPECT_GT(blended.back().cascade, 0.99f);
  EXPECT_LT(largest_step(blended), 0.06f);
  EXPECT_GT(largest_step(hard), 0.1f) << "hard seams: the test sees no jump to remove";
}

// A plate 2 units over a small ground, its straight edge at x = 0, under a
// sun almost overhead of angular diameter `alpha`.
constexpr float kPlateHeight = 2.0f;
Scene plate_scene(float alpha) {
  Scene s;
  s.name = "cascaded_plate";
  s.meshes.push_back(make_ground_plane("ground", {0.0f, 0.0f, -1.0f}, 6.0f));
  s.meshes.push_back(make_box("plate", {-2.0f, kPlateHeight, -1.0f}, {2.0f, 0.02f, 3.0f}));
  s.light = core::make_sun_light({0.0f, 1.0f, 0.05f}, {0.0f, 0.0f, -1.0f}, alpha, 80.0f);
  // Below the plate, from in front of it: the ground under it is in view.
  s.camera.eye = {0.3f, 1.0f, 5.0f};
  s.camera.target = {0.0f, 0.0f, -1.0f};
  s.camera.fov_y_degrees = 50.0f;
  s.camera.near_plane = 0.1f;
  s.camera.far_plane = 100.0f;
  return s;
}

// The exact penumbra's 10-90 % width across a straight edge at height h
// under a disk of angular diameter alpha: the disk's radius on the plane
// perpendicular to the sun is R = h·tan(alpha/2) (the sun is overhead to
// 0.05 rad), and the occluded fraction at offset u·R from the edge's shadow
// is (acos(u) − u·sqrt(1 − u²))/π, 0.1 at u = ±u10.
double exact_penumbra_width(double h, double alpha) {
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 60; ++i) {
    const double u = 0.5 * (lo + hi);
    ((std::acos(u) - u * std::sqrt(1.0 - u * u)) / 3.14159265358979 > 0.1 ? lo : hi) = u;
  }
  return 2.0 * lo * h * std::tan(0.5 * alpha);
}

// Where V first reaches `level` along the ground row through z ≈ -1 that
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
  for (int x = 0; x + 1 < kWidth; ++x) {
    const float a = v.at(x, best_row), b = v.at(x + 1, best_row);
    if (position.at(x, best_row, 0) > -1.0f && a < level && b >= level) {
      const float w = (level - a) / (b - a);
      return (1.0f - w) * position.at(x, best_row, 0) + w * position.at(x + 1, best_row, 0);
    }
  }
  return 1e30f;
}

// PCSS's penumbra under the sun is as wide as the sun's disk makes it. PCSS
// filters the hard edge with a box as wide as the predicted penumbra,
// w = (d_r − d_b)·2·tan(alpha/2) = 2h·tan(alpha/2) here, whose 10-90 % ramp
// is 0.8·w: within 20 % of that (the bilinear taps and the one-texel
// smallest filter widen it a little); the exact disk's ramp is 0.69·w, so
// the method's own error puts it 16 % wider than the exact one, checked
// loosely. The edge is centred on the hard shadow's, and the penumbra is
// twice as wide under a sun twice as large.
TEST_F(CascadedRender, PcssPenumbraGrowsWithTheSunsAngularSize) {
  double widths[2];
  for (int k = 0; k < 2; ++k) {
    const float alpha = k == 0 ? 0.2f : 0.1f;
    stage_ = std::make_unique<ContractStage>(plate_scene(alpha), kWidth, kHeight,
                                             std::vector{info_}, plugins_);
    const ImageF v = render({{"filter", "pcss"}, {"filter_taps", 9}, {"search_taps", 7}});
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

// The timing contract under the sun: check-technique's checks, with the
// light moved as a sun moves (its direction turns).
TEST_F(CascadedRender, KeepsTheTimingContractUnderTheSun) {
  stage_ = std::make_unique<ContractStage>(sun_scene(0.01f), 96, 72, std::vector{info_}, plugins_);
  const core::AreaLight first = stage_->scene().light;
  for (const char* filter : {"hard", "pcf", "pcss"}) {
    const Params p = params({{"filter", filter}, {"size", 256}});
    const auto create = [&] { return info_->create(p); };
    // The sun turned by about 10 degrees.
    const core::AreaLight second =
        core::make_sun_light(glm::normalize(kToSun + glm::vec3(-0.2f, 0.0f, 0.1f)), first.target,
                             first.angular_diameter, 80.0f);
    const ContractStage::Frames f = stage_->across_a_move(
        create, [&] { stage_->set_light(first); }, [&] { stage_->set_light(second); });
    stage_->set_light(first);
    EXPECT_EQ(run::differing_pixels(f.a_moved, f.b_moved), 0u)
        << filter << ": a frame after the sun turned differs from one prepared under it";
    EXPECT_GT(run::differing_pixels(f.a_first, f.a_moved), 0u)
        << filter << ": turning the sun changed nothing";
    for (const run::ContractCheck& c :
         {run::check_camera_move(*stage_, create, true),
          run::check_visibility_written(*stage_, create), run::check_deterministic(*stage_, create),
          run::check_gbuffer_untouched(*stage_, create)})
      EXPECT_TRUE(c.passed()) << filter << ": " << c.name << ": " << c.failure;
  }
}

// Its maps are an array of `cascades` layers of size² 32-bit depths, made
// through the metered makers: technique.gpu_bytes counts them.
TEST_F(CascadedRender, ItsGpuMemoryIsItsCascadesDepthMaps) {
  stage_for(1e-4f);
  const gl::AllocationWindow window;
  const auto t = info_->create(params({{"cascades", 3}, {"size", 512}}));
  t->prepare(stage_->inputs());
  EXPECT_EQ(window.live_bytes(), std::int64_t(3) * 512 * 512 * 4);
}

}  // namespace
}  // namespace sb::test
