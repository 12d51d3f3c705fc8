// The timing contract of Technique::prepare() and render() (plugin/technique.h),
// checked by the harness's own checks (run/timing_contract.h, which
// `shadowbench check-technique` runs on a plugin author's technique) on
// every technique the plugins register (default parameters), some modes,
// and the technique variants of configs/quick.json.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "config/experiment.h"
#include "gl/context.h"
#include "gl/debug.h"
#include "gl/pass_timer.h"
#include "plugin/registry.h"
#include "run/timing_contract.h"

namespace sb::test {

using config::Experiment;
using config::load_experiment;
using config::parse_experiment;
using config::TechniqueVariant;
using core::ImageF;
using core::Params;
using core::resolve_params;
using plugin::FrameInputs;
using plugin::Registry;
using plugin::Technique;
using plugin::TechniqueInfo;
using run::ContractCheck;
using run::ContractStage;

namespace {

constexpr int kWidth = 96;
constexpr int kHeight = 72;

// Every registered technique with its defaults, some modes, then quick.json's variants.
std::vector<TechniqueVariant> variants_under_test(const Registry& plugins) {
  nlohmann::json names = nlohmann::json::array();
  for (const TechniqueInfo& t : plugins.all()) names.push_back(t.name);
  const nlohmann::json defaults = {{"name", "defaults"},
                                   {"scenes", {{{"type", "sphere_grid"}}}},
                                   {"techniques", names},
                                   {"resolutions", {{kWidth, kHeight}}}};
  std::vector<TechniqueVariant> out = parse_experiment(defaults, "<defaults>", plugins).techniques;
  // Modes that draw passes of their own, which neither the defaults nor
  // quick.json reach (the contact option's pass among them).
  const nlohmann::json modes = {
      {"name", "modes"},
      {"scenes", {{{"type", "sphere_grid"}}}},
      {"techniques",
       {{{"name", "blurred_visibility"}, {"params", {{"space", "light"}}}},
        {{"name", "two_map_bound"}, {"params", {{"shade", {"gradient", "midpoint"}}}}},
        {{"name", "pcss"}, {"label", "pcss+contact"}, {"params", {{"contact", true}}}},
        {{"name", "contact_shadows"}, {"params", {{"length", 2.0}}}},
        {{"name", "raytraced"},
         {"params", {{"denoiser", "svgf"}, {"denoiser_temporal", {true, false}}}}}}},
      {"resolutions", {{kWidth, kHeight}}}};
  const auto extra = parse_experiment(modes, "<modes>", plugins).techniques;
  out.insert(out.end(), extra.begin(), extra.end());
  const Experiment quick =
      load_experiment(std::string(SHADOWBENCH_SOURCE_DIR) + "/configs/quick.json", plugins);
  out.insert(out.end(), quick.techniques.begin(), quick.techniques.end());
  return out;
}

// A plausible breach of the contract: it keeps the camera's matrices from
// prepare() and hands them to the technique it wraps every frame, as a
// technique that set its camera uniforms once in prepare() would.
class StaleCamera final : public Technique {
 public:
  explicit StaleCamera(std::unique_ptr<Technique> inner) : inner_(std::move(inner)) {}
  void prepare(const FrameInputs& in) override {
    inner_->prepare(in);
    prepared_ = in;
  }
  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    FrameInputs stale = in;
    stale.view = prepared_.view;
    stale.projection = prepared_.projection;
    stale.view_projection = prepared_.view_projection;
    inner_->render(stale, timer);
  }

 private:
  std::unique_ptr<Technique> inner_;
  FrameInputs prepared_;
};

class TimingContract : public ::testing::Test {
 protected:
  void SetUp() override {
    plugins_.load_plugins(SHADOWBENCH_PLUGIN_DIR);
    context_ = gl::create_context(gl::Backend::OSMesa);
    std::vector<const TechniqueInfo*> all;
    for (const TechniqueInfo& t : plugins_.all()) all.push_back(&t);
    stage_ = std::make_unique<ContractStage>(run::contract_scene(), kWidth, kHeight, all, plugins_);
  }

  // The check for every variant under test: `none` and the controls are
  // V = 1 anywhere, so moving changes nothing of theirs; contact_shadows'
  // default reach (0.5) shadows under 1 % of the pixels here (its length-2
  // variant shows the change).
  void expect_for_every_variant(ContractCheck (*check)(ContractStage&, const run::TechniqueFactory&,
                                                       bool, bool)) {
    const std::vector<TechniqueVariant> variants = variants_under_test(plugins_);
    ASSERT_GE(variants.size(), plugins_.all().size());
    for (const TechniqueVariant& tv : variants) {
      const bool expect_change =
          tv.info->name != "none" && tv.info->family != "control" && tv.name != "contact_shadows";
      const ContractCheck c = check(
          *stage_, [&] { return tv.info->create(tv.params); }, expect_change, tv.info->temporal);
      EXPECT_TRUE(c.passed()) << tv.name << ": " << c.name << ": " << c.failure;
    }
  }

  Registry plugins_;
  std::unique_ptr<gl::Context> context_;
  std::unique_ptr<ContractStage> stage_;
};

TEST_F(TimingContract, AfterTheLightMovesAFrameEqualsOnePreparedUnderTheMovedLight) {
  expect_for_every_variant(run::check_light_move);
}

TEST_F(TimingContract, AfterTheCameraMovesAFrameEqualsOnePreparedUnderTheMovedCamera) {
  expect_for_every_variant(run::check_camera_move);
}

// The check above catches a technique that keeps the camera from prepare():
// shadow_volume, handed the first camera's matrices over the second camera's
// G-buffer, draws its volumes where the first camera saw them.
TEST_F(TimingContract, TheCameraCheckCatchesATechniqueThatKeepsTheCameraFromPrepare) {
  const TechniqueInfo* volume = plugins_.find("shadow_volume");
  ASSERT_NE(volume, nullptr);
  const Params defaults = resolve_params(volume->params, nlohmann::json::object(), "", "");
  const ContractCheck c = run::check_camera_move(
      *stage_, [&] { return std::make_unique<StaleCamera>(volume->create(defaults)); }, true);
  EXPECT_FALSE(c.passed());
  EXPECT_NE(c.failure.find("pixels differ from the same technique prepared under the second "
                           "camera"),
            std::string::npos)
      << c.failure;
}

// The runner renders the G-buffer once per (scene, resolution) and restores
// only its depth-stencil between frames (run/gbuffer.h): that is fair only
// if no technique writes the colour attachments every technique reads.
TEST_F(TimingContract, NoTechniqueWritesTheGBufferColourAttachments) {
  const std::vector<ImageF> before = stage_->read_gbuffer();
  size_t covered = 0;
  for (size_t i = 0; i < before[0].pixel_count(); ++i) covered += before[0].data[i * 4 + 3] > 0.5f;
  ASSERT_GT(covered, size_t(kWidth * kHeight / 4)) << "the G-buffer shows too little of the scene";
  for (const TechniqueVariant& tv : variants_under_test(plugins_)) {
    const ContractCheck c =
        run::check_gbuffer_untouched(*stage_, [&] { return tv.info->create(tv.params); });
    EXPECT_TRUE(c.passed()) << tv.name << ": " << c.failure;
  }
}

// A temporal technique in miniature: V everywhere is a function of its
// frame count since prepare() and of the light's x where it reads it (at
// every frame, or, a breach, once in prepare()). A shared counter across
// instances (another breach) makes two instances render different frames.
class FrameCounting final : public Technique {
 public:
  enum class Light { EveryFrame, FromPrepare };
  explicit FrameCounting(Light light, int* shared = nullptr) : light_(light), shared_(shared) {}
  void prepare(const FrameInputs& in) override {
    frame_ = 0;
    prepared_x_ = in.scene->light.center.x;
  }
  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    auto pass = timer.scope("count");
    int& frame = shared_ != nullptr ? *shared_ : frame_;
    ++frame;
    const float x = light_ == Light::EveryFrame ? in.scene->light.center.x : prepared_x_;
    const float v[4] = {0.5f / float(frame) + 0.1f * (0.5f + 0.5f * std::sin(x)), 0, 0, 0};
    glClearNamedFramebufferfv(in.visibility_framebuffer, GL_COLOR, 0, v);
  }

 private:
  Light light_;
  int* shared_;
  int frame_ = 0;
  float prepared_x_ = 0;
};

// A technique whose frames depend on its frame count passes the checks as
// a temporal one, and fails "three in a row are equal" as any other: the
// temporal checks are not weaker than they need to be.
TEST_F(TimingContract, ATemporalTechniqueIsCheckedFrameByFrameAgainstAFreshInstance) {
  const auto counting = [] {
    return std::make_unique<FrameCounting>(FrameCounting::Light::EveryFrame);
  };
  EXPECT_FALSE(run::check_deterministic(*stage_, counting, false).passed());
  EXPECT_TRUE(run::check_deterministic(*stage_, counting, true).passed());
  const ContractCheck light = run::check_light_move(*stage_, counting, true, true);
  EXPECT_TRUE(light.passed()) << light.failure;
  EXPECT_FALSE(run::check_light_move(*stage_, counting, true, false).passed());

  const auto keeps_light = [] {
    return std::make_unique<FrameCounting>(FrameCounting::Light::FromPrepare);
  };
  const ContractCheck kept = run::check_light_move(*stage_, keeps_light, true, true);
  EXPECT_FALSE(kept.passed());
  EXPECT_NE(kept.failure.find("prepare() keeps something that depends on the light"),
            std::string::npos)
      << kept.failure;

  int shared = 0;
  const auto shares_state = [&] {
    return std::make_unique<FrameCounting>(FrameCounting::Light::EveryFrame, &shared);
  };
  const ContractCheck twins = run::check_deterministic(*stage_, shares_state, true);
  EXPECT_FALSE(twins.passed());
  EXPECT_NE(twins.failure.find("of a second instance differs"), std::string::npos) << twins.failure;
}

std::vector<uint32_t> read_depth_stencil(GLuint texture) {
  std::vector<uint32_t> out(size_t(kWidth) * kHeight);
  glGetTextureImage(texture, 0, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8,
                    GLsizei(out.size() * sizeof(uint32_t)), out.data());
  gl::throw_if_errors("reading the depth-stencil");
  return out;
}

// What stencil techniques leave in the shared depth-stencil (counts, a
// cleared depth) is gone when the next frame starts.
TEST_F(TimingContract, RestoringTheGBufferUndoesAFramesDepthStencilWrites) {
  const FrameInputs& in = stage_->inputs();
  const std::vector<uint32_t> pristine = read_depth_stencil(in.depth_stencil);
  size_t nearer = 0;  // geometry in front of the far plane
  for (uint32_t v : pristine) nearer += (v >> 8) < 0xffffffu ? 1 : 0;
  ASSERT_GT(nearer, size_t(kWidth * kHeight / 4));
  glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
  glClearNamedFramebufferfi(in.visibility_framebuffer, GL_DEPTH_STENCIL, 0, 0.25f, 7);
  const std::vector<uint32_t> written = read_depth_stencil(in.depth_stencil);
  ASSERT_NE(written, pristine) << "the clear did not reach the depth-stencil";
  // A frame starts with the restore.
  class Nothing final : public Technique {
    void prepare(const FrameInputs&) override {}
    void render(const FrameInputs&, gl::PassTimer&) override {}
  } nothing;
  stage_->render(nothing);
  EXPECT_EQ(read_depth_stencil(in.depth_stencil), pristine);
}

}  // namespace
}  // namespace sb::test
