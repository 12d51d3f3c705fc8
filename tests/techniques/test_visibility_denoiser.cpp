// The visibility denoiser (common/visibility_denoiser.h) on synthetic noisy
// frames whose truth is known: a ground plane seen from above, the truth a
// soft shadow edge across it, V = smoothstep over 3 world units in x, and
// each frame's input Binomial(4, V) / 4 drawn afresh per pixel (a technique
// shooting 4 shadow rays). Frames go through the harness's own frame path
// (run/timing_contract.h's ContractStage).
//   still scene:  the error falls as frames accumulate; the first frame's is
//                 no worse than the input's; the spatial-only variant's is
//                 below the input's;
//   moving light: the truth's edge jumps 4 units; three frames later the
//                 clamp has dropped the old shadow, and without rejection
//                 (the paper's SVGF) it still ghosts;
//   moving camera: reprojection keeps the history across a small pan, and
//                 drops it on ground a box hid (disocclusion);
//   edges:        on a box on the ground, the à-trous's plane and normal
//                 weights keep each surface's V from its neighbours';
//   determinism:  the same inputs give the same outputs, also after a
//                 second prepare();
//   gpu_bytes:    every texture it makes is metered.
// DISABLED_PassTimesAt640x480 prints the passes' times (not a test: run it
// with --gtest_also_run_disabled_tests --gtest_filter='*PassTimes*';
// SB_DENOISER_ITERATIONS=n sets the à-trous iterations).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/visibility_denoiser.h"
#include "core/scene_types.h"
#include "gl/allocation_meter.h"
#include "gl/context.h"
#include "gl/objects.h"
#include "plugin/registry.h"
#include "run/timing_contract.h"
#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"
#include "splitmix64_sequence.h"

namespace sb::test {
namespace {

using core::ImageF;
using core::Scene;
using run::ContractStage;
using techniques::DenoiserSettings;
using techniques::HistoryRejection;
using techniques::VisibilityDenoiser;

constexpr int kWidth = 128;
constexpr int kHeight = 96;
constexpr int kRays = 4;

Scene ground_scene() {
  Scene s;
  s.name = "denoiser_ground";
  s.meshes.push_back(make_ground_plane("ground", {0.0f, 0.0f, 0.0f}, 10.0f));
  s.light = core::make_area_light({0.0f, 6.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, 1.0f, 1.0f);
  s.camera.eye = {0.0f, 7.0f, 6.0f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.fov_y_degrees = 60.0f;
  s.camera.near_plane = 0.1f;
  s.camera.far_plane = 100.0f;
  return s;
}

// The truth: a soft edge across x = `edge`, V = 0 before it and 1 after,
// kPenumbra world units wide (about 30 pixels).
constexpr float kPenumbra = 3.0f;
std::function<float(const glm::vec3&)> soft_edge(float edge) {
  return [edge](const glm::vec3& p) {
    const float t = std::clamp((p.x - edge) / kPenumbra + 0.5f, 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
  };
}

// A technique whose V is this frame's Binomial(kRays, truth) / kRays,
// denoised.
class NoisyDenoised : public plugin::Technique {
 public:
  explicit NoisyDenoised(DenoiserSettings s) : denoiser_(s) {}
  void prepare(const plugin::FrameInputs& in) override {
    noisy_ = gl::make_texture_2d(GL_R32F, in.width, in.height);
    denoiser_.prepare(in.width, in.height);
  }
  void render(const plugin::FrameInputs& in, gl::PassTimer& timer) override {
    {
      auto pass = timer.scope("noise");
      // ImageF's rows run top-down (run::read_texture), GL's bottom-up.
      for (int y = 0; y < in.height; ++y)
        glTextureSubImage2D(noisy_.get(), 0, 0, in.height - 1 - y, in.width, 1, GL_RED, GL_FLOAT,
                            &input.at(0, y));
    }
    denoiser_.denoise(in, noisy_.get(), timer);
  }
  ImageF input;  // this frame's noisy V

 private:
  VisibilityDenoiser denoiser_;
  gl::Texture noisy_;
};

class VisibilityDenoiserTest : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = gl::create_context(gl::Backend::OSMesa);
    stage_ = std::make_unique<ContractStage>(ground_scene(), kWidth, kHeight,
                                             std::vector<const plugin::TechniqueInfo*>{}, plugins_);
    position_ = stage_->read_gbuffer()[0];
  }
  void look_through(const core::Camera& camera) {
    stage_->look_through(camera);
    position_ = stage_->read_gbuffer()[0];
  }
  bool geometry(int x, int y) const { return position_.at(x, y, 3) != 0.0f; }
  glm::vec3 point(int x, int y) const {
    return {position_.at(x, y, 0), position_.at(x, y, 1), position_.at(x, y, 2)};
  }
  ImageF truth_image(const std::function<float(const glm::vec3&)>& truth) const {
    ImageF t(kWidth, kHeight, 1, 1.0f);
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        if (geometry(x, y)) t.at(x, y) = truth(point(x, y));
    return t;
  }
  // Binomial(kRays, truth) / kRays per pixel, from stream `seed`.
  ImageF noisy_image(const ImageF& truth, uint64_t seed) const {
    const std::vector<float> u = sbtest::splitmix64_uniforms(seed, kWidth * kHeight * kRays);
    ImageF n(kWidth, kHeight, 1, 1.0f);
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        int hits = 0;
        for (int r = 0; r < kRays; ++r)
          hits += u[(size_t(y) * kWidth + size_t(x)) * kRays + size_t(r)] < truth.at(x, y);
        n.at(x, y) = float(hits) / float(kRays);
      }
    return n;
  }
  ImageF frame(NoisyDenoised& t, const ImageF& truth, uint64_t seed) {
    t.input = noisy_image(truth, seed);
    return stage_->render(t);
  }
  // Where the truth is fractional: the noise is there (and nowhere else).
  static std::function<bool(int, int)> penumbra(const ImageF& truth) {
    return [&truth](int x, int y) { return truth.at(x, y) > 0.01f && truth.at(x, y) < 0.99f; };
  }
  // RMSE over geometry pixels where `mask` holds.
  double rmse(const ImageF& v, const ImageF& truth,
              const std::function<bool(int, int)>& mask = nullptr) const {
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        if (!geometry(x, y) || (mask && !mask(x, y))) continue;
        const double d = double(v.at(x, y)) - double(truth.at(x, y));
        sum += d * d;
        ++n;
      }
    EXPECT_GT(n, 500);
    return std::sqrt(sum / std::max(n, 1));
  }
  // The ground with a box on it, each surface its own V: the top 0.5, the
  // sides 0.75, the ground 0.25.
  void use_box_scene() {
    Scene scene = ground_scene();
    scene.meshes.push_back(make_box("box", {0.0f, 1.0f, 0.0f}, {1.5f, 1.0f, 1.5f}));
    stage_ = std::make_unique<ContractStage>(scene, kWidth, kHeight,
                                             std::vector<const plugin::TechniqueInfo*>{}, plugins_);
    position_ = stage_->read_gbuffer()[0];
  }
  ImageF surface_truth() const {
    const ImageF normal = stage_->read_gbuffer()[1];
    ImageF truth(kWidth, kHeight, 1, 1.0f);
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        if (geometry(x, y))
          truth.at(x, y) = normal.at(x, y, 1) < 0.5f ? 0.75f : point(x, y).y > 1.0f ? 0.5f : 0.25f;
    return truth;
  }
  // Sixteen frames of truth `a`, then three of `b`: the last frame's error.
  double error_after_the_light_moved(NoisyDenoised& t, const ImageF& a, const ImageF& b,
                                     const std::function<double(const ImageF&)>& error) {
    for (uint64_t k = 1; k <= 16; ++k) frame(t, a, k);
    ImageF v;
    for (uint64_t k = 17; k <= 19; ++k) v = frame(t, b, k);
    return error(v);
  }

  plugin::Registry plugins_;
  std::unique_ptr<gl::Context> context_;
  std::unique_ptr<ContractStage> stage_;
  ImageF position_;
};

TEST_F(VisibilityDenoiserTest, StillSceneConvergesTowardTheTruth) {
  const ImageF truth = truth_image(soft_edge(0.0f));
  NoisyDenoised t({});
  t.prepare(stage_->inputs());
  const ImageF first = frame(t, truth, 1);
  const double input_error = rmse(t.input, truth, penumbra(truth));
  const double first_error = rmse(first, truth, penumbra(truth));
  ImageF last;
  for (uint64_t k = 2; k <= 16; ++k) last = frame(t, truth, k);
  const double last_error = rmse(last, truth, penumbra(truth));
  // The clamp costs the still scene little: the paper's (no rejection)
  // after as many frames.
  DenoiserSettings paper;
  paper.rejection = HistoryRejection::None;
  NoisyDenoised none(paper);
  none.prepare(stage_->inputs());
  ImageF none_last;
  for (uint64_t k = 1; k <= 16; ++k) none_last = frame(none, truth, k);
  const double none_error = rmse(none_last, truth, penumbra(truth));
  std::printf("input %.4f, frame 1 %.4f, frame 16 %.4f (without rejection %.4f)\n", input_error,
              first_error, last_error, none_error);
  EXPECT_LE(first_error, input_error);
  EXPECT_LT(last_error, 0.6 * first_error);
  EXPECT_LT(last_error, 1.5 * none_error);
  // Background pixels read 1.
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      if (!geometry(x, y)) {
        ASSERT_EQ(last.at(x, y), 1.0f) << x << ", " << y;
      }
}

TEST_F(VisibilityDenoiserTest, SpatialOnlyReducesTheInputsError) {
  const ImageF truth = truth_image(soft_edge(0.0f));
  DenoiserSettings s;
  s.temporal = false;
  NoisyDenoised t(s);
  t.prepare(stage_->inputs());
  for (uint64_t k = 1; k <= 3; ++k) {
    const ImageF v = frame(t, truth, k);
    const double input_error = rmse(t.input, truth, penumbra(truth));
    const double error = rmse(v, truth, penumbra(truth));
    std::printf("spatial only, frame %d: input %.4f, denoised %.4f\n", int(k), input_error, error);
    EXPECT_LT(error, 0.7 * input_error);
  }
}

TEST_F(VisibilityDenoiserTest, ClampDropsAMovedLightsOldShadowAndNoneGhosts) {
  const ImageF a = truth_image(soft_edge(-2.0f)), b = truth_image(soft_edge(2.0f));
  const auto changed = [&](int x, int y) { return std::abs(a.at(x, y) - b.at(x, y)) > 0.5f; };
  const auto error = [&](const ImageF& v) { return rmse(v, b, changed); };
  NoisyDenoised clamped({});
  clamped.prepare(stage_->inputs());
  const double clamp_error = error_after_the_light_moved(clamped, a, b, error);
  DenoiserSettings s;
  s.rejection = HistoryRejection::None;
  NoisyDenoised paper(s);
  paper.prepare(stage_->inputs());
  const double none_error = error_after_the_light_moved(paper, a, b, error);
  std::printf("where the light's move changed V, 3 frames on: clamp %.4f, none %.4f\n", clamp_error,
              none_error);
  // Clamping without restarting the history leaves about 0.06 here.
  EXPECT_LT(clamp_error, 0.04);
  EXPECT_GT(none_error, 0.2);
}

TEST_F(VisibilityDenoiserTest, ReprojectionKeepsTheHistoryAcrossACameraPan) {
  NoisyDenoised t({});
  t.prepare(stage_->inputs());
  const ImageF truth = truth_image(soft_edge(0.0f));
  ImageF v;
  // Errors fluctuate by about 15% from frame to frame: means of a few.
  double before = 0.0;
  for (uint64_t k = 1; k <= 16; ++k) {
    v = frame(t, truth, k);
    if (k > 12) before += rmse(v, truth, penumbra(truth)) / 4.0;
  }
  const glm::mat4 first_view_projection = stage_->inputs().view_projection;
  // A pan of about 8 pixels: the ground seen before is seen again, nothing
  // disoccluded; compared only where the pixel was on screen before.
  core::Camera moved = stage_->scene().camera;
  moved.eye += glm::vec3(0.8f, 0.0f, 0.0f);
  moved.target += glm::vec3(0.8f, 0.0f, 0.0f);
  look_through(moved);
  const ImageF moved_truth = truth_image(soft_edge(0.0f));
  const auto compared = [&](int x, int y) {
    const glm::vec4 c = first_view_projection * glm::vec4(point(x, y), 1.0f);
    return penumbra(moved_truth)(x, y) && c.w > 0.0f && std::abs(c.x / c.w) < 0.95f &&
           std::abs(c.y / c.w) < 0.95f;
  };
  double after = 0.0;
  for (uint64_t k = 17; k <= 18; ++k)
    after += rmse(frame(t, moved_truth, k), moved_truth, compared) / 2.0;
  // A fresh start's error two frames in, for scale.
  NoisyDenoised fresh({});
  fresh.prepare(stage_->inputs());
  double restarted = 0.0;
  for (uint64_t k = 17; k <= 18; ++k)
    restarted += rmse(frame(fresh, moved_truth, k), moved_truth, compared) / 2.0;
  std::printf("before the pan %.4f, 2 frames after %.4f, a restart's %.4f\n", before, after,
              restarted);
  EXPECT_LT(after, 1.4 * before);
  EXPECT_LT(after, 0.75 * restarted);
}

TEST_F(VisibilityDenoiserTest, SameInputsGiveTheSameOutputs) {
  const ImageF a = truth_image(soft_edge(-1.0f)), b = truth_image(soft_edge(1.5f));
  const auto run = [&](NoisyDenoised& t) {
    std::vector<ImageF> out;
    for (uint64_t k = 1; k <= 6; ++k) out.push_back(frame(t, k <= 3 ? a : b, k));
    return out;
  };
  NoisyDenoised one({}), two({});
  one.prepare(stage_->inputs());
  two.prepare(stage_->inputs());
  const std::vector<ImageF> first = run(one), second = run(two);
  // Prepared again, `one` forgets its history: the same frames again.
  one.prepare(stage_->inputs());
  const std::vector<ImageF> again = run(one);
  for (size_t k = 0; k < first.size(); ++k) {
    EXPECT_EQ(run::differing_pixels(first[k], second[k]), 0u) << "frame " << k + 1;
    EXPECT_EQ(run::differing_pixels(first[k], again[k]), 0u) << "frame " << k + 1;
  }
}

// A box on the ground, each surface its own V: the top 0.5, the sides 0.75,
// the ground 0.25 (each frame's input noisy around them). Near the box's
// outline, the à-trous taps across it must weigh nothing: with its plane and
// normal tests the error there is a fraction of what the same filter without
// them (sigma_plane huge, sigma_normal 0) leaves.
TEST_F(VisibilityDenoiserTest, EdgeStoppingKeepsSurfacesApart) {
  use_box_scene();
  const ImageF truth = surface_truth();
  // Pixels within 3 of another surface's (background aside).
  const auto near_outline = [&](int x, int y) {
    for (int dy = -3; dy <= 3; ++dy)
      for (int dx = -3; dx <= 3; ++dx) {
        const int u = std::clamp(x + dx, 0, kWidth - 1), v = std::clamp(y + dy, 0, kHeight - 1);
        if (geometry(u, v) && truth.at(u, v) != truth.at(x, y)) return true;
      }
    return false;
  };
  DenoiserSettings with;
  with.temporal = false;
  DenoiserSettings without = with;
  without.sigma_plane = 1e6f;
  without.sigma_normal = 0.0f;
  NoisyDenoised stopped(with), blurred(without);
  stopped.prepare(stage_->inputs());
  blurred.prepare(stage_->inputs());
  const ImageF a = frame(stopped, truth, 1);
  const double input_error = rmse(stopped.input, truth, near_outline);
  const double stopped_error = rmse(a, truth, near_outline);
  const double blurred_error = rmse(frame(blurred, truth, 1), truth, near_outline);
  std::printf(
      "near the box's outline: input %.4f, edge-stopped %.4f, without the geometry "
      "weights %.4f\n",
      input_error, stopped_error, blurred_error);
  EXPECT_LT(stopped_error, 0.5 * input_error);
  EXPECT_LT(stopped_error, 0.6 * blurred_error);
}

// The camera moves past the box: ground it hid comes into view. Without
// the clamp (rejection none, the paper's), only the reprojection's plane and
// normal tests keep those pixels from the box's history: one frame after the
// move their error is a fraction of what it is with the plane test
// disabled (reprojection_tolerance huge).
TEST_F(VisibilityDenoiserTest, DisocclusionRestartsTheHistory) {
  use_box_scene();
  const core::Camera first = stage_->scene().camera;
  core::Camera moved = first;
  moved.eye += glm::vec3(2.0f, 0.0f, 0.0f);
  const auto error_where_disoccluded = [&](DenoiserSettings s) {
    look_through(first);
    const ImageF before = position_;
    const glm::mat4 first_view_projection = stage_->inputs().view_projection;
    NoisyDenoised t(s);
    t.prepare(stage_->inputs());
    for (uint64_t k = 1; k <= 16; ++k) frame(t, surface_truth(), k);
    look_through(moved);
    const ImageF truth = surface_truth();
    const ImageF v = frame(t, truth, 17);
    // Ground pixels where the first view saw the box's top (which faces
    // the same way: only the plane test tells them apart).
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        if (!geometry(x, y)) continue;
        const glm::vec4 c = first_view_projection * glm::vec4(point(x, y), 1.0f);
        const int u = int(std::floor((c.x / c.w * 0.5f + 0.5f) * kWidth));
        const int w = kHeight - 1 - int(std::floor((c.y / c.w * 0.5f + 0.5f) * kHeight));
        if (u < 0 || u >= kWidth || w < 0 || w >= kHeight || before.at(u, w, 3) == 0.0f) continue;
        const glm::vec3 seen{before.at(u, w, 0), before.at(u, w, 1), before.at(u, w, 2)};
        if (seen.y < 1.99f || point(x, y).y > 0.01f) continue;
        const double d = double(v.at(x, y)) - double(truth.at(x, y));
        sum += d * d;
        ++n;
      }
    EXPECT_GT(n, 100);
    return std::sqrt(sum / std::max(n, 1));
  };
  DenoiserSettings tested;
  tested.rejection = HistoryRejection::None;
  DenoiserSettings untested = tested;
  untested.reprojection_tolerance = 1e6f;
  const double rejected = error_where_disoccluded(tested);
  const double kept = error_where_disoccluded(untested);
  std::printf("disoccluded pixels, a frame after the move: %.4f, without the plane test %.4f\n",
              rejected, kept);
  EXPECT_LT(rejected, 0.3 * kept);
}

// The iteration counts with their own paths: none (V copied: without
// temporal, the input itself) and one (V written straight into the target,
// the history copied from it).
TEST_F(VisibilityDenoiserTest, NoneOrOneIteration) {
  const ImageF truth = truth_image(soft_edge(0.0f));
  DenoiserSettings copy;
  copy.temporal = false;
  copy.atrous_iterations = 0;
  NoisyDenoised identity(copy);
  identity.prepare(stage_->inputs());
  const ImageF v = frame(identity, truth, 1);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      ASSERT_EQ(v.at(x, y), geometry(x, y) ? identity.input.at(x, y) : 1.0f) << x << ", " << y;
  DenoiserSettings one;
  one.atrous_iterations = 1;
  NoisyDenoised t(one);
  t.prepare(stage_->inputs());
  const double first = rmse(frame(t, truth, 1), truth, penumbra(truth));
  ImageF last;
  for (uint64_t k = 2; k <= 16; ++k) last = frame(t, truth, k);
  const double sixteenth = rmse(last, truth, penumbra(truth));
  std::printf("one iteration: frame 1 %.4f, frame 16 %.4f\n", first, sixteenth);
  EXPECT_LT(sixteenth, 0.6 * first);
}

// gpu_bytes: the histories (per pixel and frame of the two: V, m1, m2 and
// length in RGBA32F, the filtered V in R32F, the position in RGBA32F, the
// normal in RGBA16F), the clamp's window sums (RGBA32F) and the two guides
// (RGBA32F), all metered; without temporal, the guides only.
TEST_F(VisibilityDenoiserTest, MetersItsTextures) {
  const std::int64_t pixels = kWidth * kHeight;
  for (const bool temporal : {true, false}) {
    DenoiserSettings s;
    s.temporal = temporal;
    VisibilityDenoiser d(s);
    gl::AllocationWindow window;
    d.prepare(kWidth, kHeight);
    const std::int64_t history = 2 * (16 + 4 + 16 + 8) + 16;
    EXPECT_EQ(window.live_bytes(), pixels * ((temporal ? history : 0) + 2 * 16)) << temporal;
  }
}

// A technique's denoiser parameters: declared with their defaults, every
// one read (config/unread_params.h), "none" turning the denoiser off.
TEST(DenoiserParams, ReadIntoSettings) {
  const std::vector<core::ParamSpec> specs = techniques::denoiser_params("none");
  const core::Params defaults = core::resolve_params(specs, nlohmann::json::object(), "", "");
  EXPECT_FALSE(techniques::denoiser_settings(defaults).has_value());
  EXPECT_TRUE(defaults.unread().empty());
  const core::Params given = core::resolve_params(specs,
                                                  {{"denoiser", "svgf"},
                                                   {"denoiser_temporal", false},
                                                   {"denoiser_rejection", "none"},
                                                   {"denoiser_iterations", 2},
                                                   {"denoiser_alpha", 0.5},
                                                   {"denoiser_clamp_gamma", 2.0}},
                                                  "", "");
  const std::optional<DenoiserSettings> s = techniques::denoiser_settings(given);
  ASSERT_TRUE(s.has_value());
  EXPECT_FALSE(s->temporal);
  EXPECT_EQ(s->rejection, HistoryRejection::None);
  EXPECT_EQ(s->atrous_iterations, 2);
  EXPECT_EQ(s->alpha, 0.5f);
  EXPECT_EQ(s->clamp_gamma, 2.0f);
  EXPECT_EQ(
      techniques::denoiser_settings(core::resolve_params(specs, {{"denoiser", "svgf"}}, "", ""))
          ->rejection,
      HistoryRejection::Clamp);
}

// Not a test: the passes' times at 640x480, median of 8 frames after 4.
TEST(VisibilityDenoiserTimes, DISABLED_PassTimesAt640x480) {
  const auto context = gl::create_context(gl::Backend::OSMesa);
  plugin::Registry plugins;
  for (const bool temporal : {true, false}) {
    ContractStage stage(ground_scene(), 640, 480, {}, plugins);
    DenoiserSettings s;
    s.temporal = temporal;
    if (const char* n = std::getenv("SB_DENOISER_ITERATIONS")) s.atrous_iterations = std::atoi(n);
    NoisyDenoised t(s);
    t.prepare(stage.inputs());
    t.input = ImageF(640, 480, 1, 0.5f);
    std::map<std::string, std::vector<double>> times;
    for (int k = 0; k < 12; ++k) {
      gl::reset_state();
      gl::PassTimer timer(gl::TimingSource::CpuFinish, gl::PassDetail::Fine);
      timer.begin_frame();
      t.render(stage.inputs(), timer);  // fine detail: the passes at top level
      const gl::PassTimer::Frame f = timer.end_frame();
      if (k >= 4)
        for (const auto& [pass, ms] : f.passes) times[pass].push_back(ms);
    }
    for (auto& [pass, ms] : times) {
      std::sort(ms.begin(), ms.end());
      std::printf("temporal %s, %s: %.2f ms (median of %zu)\n", temporal ? "on" : "off",
                  pass.c_str(), ms[ms.size() / 2], ms.size());
    }
  }
}

}  // namespace
}  // namespace sb::test
