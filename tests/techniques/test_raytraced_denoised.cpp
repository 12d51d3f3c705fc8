// raytraced with the kit's denoiser (common/visibility_denoiser.h) on a real
// scene, against a 1024-sample Monte Carlo reference (the sphere grid's
// triangles, `analytic: false`): a still scene converges towards the
// reference as frames accumulate; under a light that jumps, history is
// rejected where visibility changed with the clamp, and ghosts without it
// (the paper's SVGF, `denoiser_rejection: none`).
//
// With SB_RAYTRACED_IMAGES=<folder> set, V is written there as PGM images.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "core/scene_types.h"
#include "debug_images.h"
#include "gl/context.h"
#include "plugin/registry.h"
#include "reference/reference.h"
#include "run/timing_contract.h"
#include "scenes/sphere_grid.h"

namespace sb::test {
namespace {

using core::ImageF;
using core::Scene;
using plugin::Registry;
using plugin::TechniqueInfo;
using run::ContractStage;

// Large enough that a sphere's shadow spans tens of pixels: at 96×72 the
// à-trous passes' 33-pixel reach blurs the grid's shadows away.
constexpr int kWidth = 320;
constexpr int kHeight = 240;

Scene sphere_grid() {
  const core::SceneType* t = core::find_scene_type("sphere_grid");
  return t->build(core::resolve_params(t->params, {{"analytic", false}}, "test", "/params"));
}

void maybe_write(const ImageF& img, const std::string& name) {
  write_pgm_if_asked(img, "SB_RAYTRACED_IMAGES", name, true);
}

class RaytracedDenoised : public ::testing::Test {
 protected:
  void SetUp() override {
    plugins_.load_plugins(SHADOWBENCH_PLUGIN_DIR);
    context_ = gl::create_context(gl::Backend::OSMesa);
    info_ = plugins_.find("raytraced");
    ASSERT_NE(info_, nullptr);
    stage_ = std::make_unique<ContractStage>(sphere_grid(), kWidth, kHeight, std::vector{info_},
                                             plugins_);
  }

  std::unique_ptr<plugin::Technique> make(const nlohmann::json& params) const {
    return info_->create(core::resolve_params(info_->params, params, "", ""));
  }

  // The reference of the stage's current light at 1024 samples.
  ImageF truth() {
    const std::vector<ImageF> g = stage_->read_gbuffer();
    return reference::compute(stage_->scene(), g[0], g[1], reference::Settings(1024, 5)).visibility;
  }

  // RMSE over the covered pixels where `where` holds (all covered when empty).
  double rmse(const ImageF& v, const ImageF& t, const std::vector<bool>& where = {}) {
    const ImageF positions = stage_->read_gbuffer()[0];
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < v.pixel_count(); ++i) {
      if (!(positions.data[i * 4 + 3] > 0.5f) || (!where.empty() && !where[i])) continue;
      const double d = double(v.data[i]) - double(t.data[i]);
      sum += d * d;
      ++n;
    }
    EXPECT_GT(n, size_t(50));
    return std::sqrt(sum / double(std::max<size_t>(n, 1)));
  }

  Registry plugins_;
  std::unique_ptr<gl::Context> context_;
  const TechniqueInfo* info_ = nullptr;
  std::unique_ptr<ContractStage> stage_;
};

TEST_F(RaytracedDenoised, AStillSceneConvergesTowardsTheReferenceAsFramesAccumulate) {
  const ImageF t = truth();
  const auto noisy = make({{"spp", 1}});
  noisy->prepare(stage_->inputs());
  const double raw = rmse(stage_->render(*noisy), t);

  const auto svgf = make({{"spp", 1}, {"denoiser", "svgf"}});
  svgf->prepare(stage_->inputs());
  std::vector<double> by_frame;
  for (int frame = 1; frame <= 16; ++frame) {
    const ImageF v = stage_->render(*svgf);
    by_frame.push_back(rmse(v, t));
    if (frame == 1 || frame == 16) maybe_write(v, "svgf_frame" + std::to_string(frame));
  }
  const auto spatial = make({{"spp", 1}, {"denoiser", "svgf"}, {"denoiser_temporal", false}});
  spatial->prepare(stage_->inputs());
  double spatial_rmse = 0.0;
  for (int frame = 1; frame <= 4; ++frame) spatial_rmse = rmse(stage_->render(*spatial), t);
  std::printf("1 spp: RMSE %.4f raw, %.4f spatial only; svgf frame 1 %.4f, 4 %.4f, 16 %.4f\n", raw,
              spatial_rmse, by_frame[0], by_frame[3], by_frame[15]);
  EXPECT_LT(by_frame[0], raw);
  EXPECT_LT(spatial_rmse, 0.8 * raw);
  EXPECT_LT(by_frame[3], by_frame[0]);
  EXPECT_LT(by_frame[15], 0.85 * by_frame[0]);
  EXPECT_LT(by_frame[15], 0.6 * raw);
}

TEST_F(RaytracedDenoised, AJumpingLightRejectsHistoryWhereVisibilityChanged) {
  const core::AreaLight first = stage_->scene().light;
  core::AreaLight second = first;
  // A jump of a third of the casters' extent: every shadow moves by many pixels.
  const core::Bounds b = stage_->scene().caster_bounds();
  second.center += glm::normalize(first.half_u) * (0.66f * b.radius());
  second.target += glm::normalize(first.half_u) * (0.66f * b.radius());
  const ImageF truth_first = truth();
  stage_->set_light(second);
  const ImageF truth_second = truth();
  std::vector<bool> changed(truth_first.pixel_count());
  size_t n_changed = 0;
  for (size_t i = 0; i < changed.size(); ++i) {
    changed[i] = std::abs(truth_first.data[i] - truth_second.data[i]) > 0.5f;
    n_changed += changed[i];
  }
  ASSERT_GT(n_changed, size_t(200)) << "the jump moves too few shadows to tell";

  const auto after_jump = [&](const std::string& rejection) {
    const auto t = make({{"spp", 4}, {"denoiser", "svgf"}, {"denoiser_rejection", rejection}});
    stage_->set_light(first);
    t->prepare(stage_->inputs());
    for (int frame = 1; frame <= 16; ++frame) (void)stage_->render(*t);
    stage_->set_light(second);
    ImageF v;
    for (int frame = 1; frame <= 3; ++frame) v = stage_->render(*t);
    maybe_write(v, "jump_" + rejection);
    return rmse(v, truth_second, changed);
  };
  const double clamp = after_jump("clamp"), none = after_jump("none");
  stage_->set_light(first);
  std::printf("3 frames after the jump, RMSE where V changed (%zu px): clamp %.4f, none %.4f\n",
              n_changed, clamp, none);
  EXPECT_LT(clamp, 0.25);
  EXPECT_GT(none, 0.35);
  EXPECT_LT(clamp, 0.5 * none);
}

}  // namespace
}  // namespace sb::test
