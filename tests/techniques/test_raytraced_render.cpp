// raytraced against the Monte Carlo reference (reference/reference.h) at
// the same sample count, on the very G-buffer both read: the sphere grid
// (triangles, `analytic: false`, so both trace the same surfaces) under its
// square light, a segment and the sun, and foliage (alpha-masked leaves).
// Both estimate the same V with zero-mean noise, so per pixel
//   z = (V_rt - V_ref) / sqrt(σ_rt² + σ_ref²),  σ² = p(1 - p)/N each,
// p from a 1024-sample reference (the binomial variance, which stratified
// sampling never exceeds and a scrambled (0, m, 2)-net exceeds by at most
// 2×, Owen 1997), and over the penumbra (0 < p < 1):
//   - the mean of z within 4 of its standard errors of 0,
//   - the mean of z² at most 1.5 (the bound above),
//   - under 1% of the covered pixels beyond 4σ,
//   - the mean squared difference of the two estimates no more than the
//     noise alone gives (half the squared differences of two independent
//     frames plus two reference seeds), within 4 standard errors.
// Measured on llvmpipe with the technique broken on purpose: the light's
// samples shifted by 3% of its side fail on the sphere grid (the mean of z),
// by 2% along the segment, the sun's by 5% of its radius (the last check),
// and leaves traced without their masks fail all four.
// Also: a plate over the ground against its closed-form V, a point light's
// hard shadow against the reference's, no casters, frames that differ with
// nothing moved (the frame index scrambles the samples), and the GPU memory
// the casters take.
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

#include "core/scene_types.h"
#include "debug_images.h"
#include "gl/allocation_meter.h"
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

constexpr int kWidth = 96;
constexpr int kHeight = 72;
constexpr int kTruthSpp = 1024;

Scene scene_of(const std::string& type, const nlohmann::json& params) {
  const core::SceneType* t = core::find_scene_type(type);
  EXPECT_NE(t, nullptr) << type;
  return t->build(core::resolve_params(t->params, params, "test", "/params"));
}

void maybe_write(const ImageF& img, const std::string& name) {
  write_pgm_if_asked(img, "SB_RAYTRACED_IMAGES", name, true);
}

struct Agreement {
  int covered = 0;
  int penumbra = 0;     // covered pixels with 0 < p < 1
  double mean_z = 0.0;  // over the penumbra
  double standard_error = 0.0;
  double mean_z2 = 0.0;       // over the penumbra
  double share_beyond = 0.0;  // of the covered pixels, |z| > 4
  double mean_rt = 0.0, mean_ref = 0.0;
  // Over the penumbra: the squared differences of the two estimates against
  // what the noise alone gives them, from two independent frames and two
  // reference seeds; 1 unless the expectations differ. And its standard error.
  double noise_ratio = 0.0, noise_ratio_error = 0.0;
};

class RaytracedRender : public ::testing::Test {
 protected:
  void SetUp() override {
    plugins_.load_plugins(SHADOWBENCH_PLUGIN_DIR);
    context_ = gl::create_context(gl::Backend::OSMesa);
    info_ = plugins_.find("raytraced");
    ASSERT_NE(info_, nullptr);
  }

  std::unique_ptr<plugin::Technique> make(int spp, const std::string& sequence = "sobol") const {
    return info_->create(
        core::resolve_params(info_->params, {{"spp", spp}, {"sequence", sequence}}, "", ""));
  }

  Agreement agreement(const Scene& scene, int spp, const std::string& name,
                      const std::string& sequence) {
    ContractStage stage(scene, kWidth, kHeight, {info_}, plugins_);
    EXPECT_EQ(stage.skip_reason(0), "");
    const auto t = make(spp, sequence);
    t->prepare(stage.inputs());
    const ImageF v = stage.render(*t);
    const ImageF v2 = stage.render(*t);  // the next frame: other samples
    const std::vector<ImageF> g = stage.read_gbuffer();
    const reference::Result ref =
        reference::compute(stage.scene(), g[0], g[1], reference::Settings(spp, 7));
    const reference::Result ref2 =
        reference::compute(stage.scene(), g[0], g[1], reference::Settings(spp, 8));
    const reference::Result truth =
        reference::compute(stage.scene(), g[0], g[1], reference::Settings(kTruthSpp, 9));
    maybe_write(v, name + "_raytraced");
    maybe_write(ref.visibility, name + "_reference");
    maybe_write(truth.visibility, name + "_truth");
    Agreement a;
    double sum = 0.0, sum2 = 0.0;
    int beyond = 0;
    std::vector<double> apart, noise;  // per penumbra pixel
    for (size_t i = 0; i < v.pixel_count(); ++i) {
      if (!(g[0].data[i * 4 + 3] > 0.5f)) continue;
      ++a.covered;
      a.mean_rt += v.data[i];
      a.mean_ref += ref.visibility.data[i];
      const double truth_v = truth.visibility.data[i];
      // p at 0 or 1 (no sample of 1024 disagreed) keeps half a sample's
      // variance, so that a disagreement there counts as far out.
      const double p = std::clamp(truth_v, 0.5 / kTruthSpp, 1.0 - 0.5 / kTruthSpp);
      const double sigma = std::sqrt(2.0 * p * (1.0 - p) / spp);
      const double z = (double(v.data[i]) - double(ref.visibility.data[i])) / sigma;
      beyond += std::abs(z) > 4.0;
      if (truth_v > 0.0 && truth_v < 1.0) {
        ++a.penumbra;
        sum += z;
        sum2 += z * z;
        const double d = double(v.data[i]) - ref.visibility.data[i];
        const double d_rt = double(v.data[i]) - v2.data[i];
        const double d_ref = double(ref.visibility.data[i]) - ref2.visibility.data[i];
        apart.push_back(d * d);
        noise.push_back(0.5 * (d_rt * d_rt + d_ref * d_ref));
      }
    }
    a.mean_rt /= std::max(a.covered, 1);
    a.mean_ref /= std::max(a.covered, 1);
    a.mean_z = sum / std::max(a.penumbra, 1);
    a.mean_z2 = sum2 / std::max(a.penumbra, 1);
    const double var = a.mean_z2 - a.mean_z * a.mean_z;
    a.standard_error = std::sqrt(std::max(var, 0.0) / std::max(a.penumbra - 1, 1));
    a.share_beyond = double(beyond) / std::max(a.covered, 1);
    // A ratio of means; its standard error by the delta method.
    double mean_apart = 0.0, mean_noise = 0.0;
    for (size_t k = 0; k < apart.size(); ++k) {
      mean_apart += apart[k] / double(apart.size());
      mean_noise += noise[k] / double(apart.size());
    }
    a.noise_ratio = mean_apart / mean_noise;
    double spread = 0.0;
    for (size_t k = 0; k < apart.size(); ++k) {
      const double r = apart[k] - a.noise_ratio * noise[k];
      spread += r * r / double(apart.size() - 1);
    }
    a.noise_ratio_error = std::sqrt(spread / double(apart.size())) / mean_noise;
    std::printf(
        "%-22s %2d spp: %5d covered, %4d penumbra; mean V %.4f (reference %.4f); mean z %+.3f "
        "± %.3f, mean z² %.3f, %.2f%% beyond 4σ; noise ratio %.3f ± %.3f\n",
        name.c_str(), spp, a.covered, a.penumbra, a.mean_rt, a.mean_ref, a.mean_z, a.standard_error,
        a.mean_z2, 100.0 * a.share_beyond, a.noise_ratio, a.noise_ratio_error);
    return a;
  }

  void expect_same_expectation(const Scene& scene, int spp, const std::string& name,
                               const std::string& sequence = "sobol") {
    const Agreement a = agreement(scene, spp, name, sequence);
    ASSERT_GT(a.covered, kWidth * kHeight / 3);
    ASSERT_GT(a.penumbra, 150) << "too few soft pixels to tell";
    EXPECT_LT(std::abs(a.mean_z), 4.0 * a.standard_error);
    EXPECT_LT(a.mean_z2, 1.5);
    EXPECT_LT(a.share_beyond, 0.01);
    EXPECT_LT(a.noise_ratio, 1.0 + 4.0 * a.noise_ratio_error);
  }

  Registry plugins_;
  std::unique_ptr<gl::Context> context_;
  const TechniqueInfo* info_ = nullptr;
};

Scene sphere_grid() { return scene_of("sphere_grid", {{"analytic", false}}); }

TEST_F(RaytracedRender, SameExpectedVAsTheReferenceOnTheSphereGrid) {
  for (int spp : {4, 16, 64}) expect_same_expectation(sphere_grid(), spp, "sphere_grid");
}

TEST_F(RaytracedRender, SameExpectedVAsTheReferenceUnderASegmentLight) {
  Scene s = sphere_grid();
  s.light.half_v = glm::vec3(0.0f);  // a segment along half_u
  expect_same_expectation(s, 16, "sphere_grid_segment");
}

TEST_F(RaytracedRender, SameExpectedVAsTheReferenceUnderTheSun) {
  Scene s = sphere_grid();
  // 11° across, so the penumbrae are several pixels wide.
  s.light = core::make_sun_light({0.3f, 1.0f, 0.2f}, {0.0f, 0.0f, 0.0f}, 0.2f, 30.0f);
  expect_same_expectation(s, 64, "sphere_grid_sun");
}

TEST_F(RaytracedRender, SameExpectedVAsTheReferenceThroughTheLeavesMasks) {
  for (int spp : {4, 16})
    expect_same_expectation(scene_of("foliage", {{"trees", 2}}), spp, "foliage");
}

// A point light (size 0) leaves nothing to sample: every sample of both is
// the light's centre, so V is 0 or 1 and must be the reference's but where
// the two traversals' rounding differ on a silhouette (a few pixels).
TEST_F(RaytracedRender, UnderAPointLightVIsTheReferencesHardShadow) {
  Scene s = scene_of("sphere_grid", {{"analytic", false}, {"light_size", 0.0}});
  ASSERT_TRUE(s.light.is_point());
  ContractStage stage(s, kWidth, kHeight, {info_}, plugins_);
  ASSERT_EQ(stage.skip_reason(0), "");
  const auto t = make(4);
  t->prepare(stage.inputs());
  const ImageF v = stage.render(*t);
  const std::vector<ImageF> g = stage.read_gbuffer();
  const reference::Result ref =
      reference::compute(stage.scene(), g[0], g[1], reference::Settings(4, 7));
  int covered = 0, shadowed = 0, differ = 0;
  for (size_t i = 0; i < v.pixel_count(); ++i) {
    if (!(g[0].data[i * 4 + 3] > 0.5f)) continue;
    ++covered;
    shadowed += ref.visibility.data[i] == 0.0f;
    differ += v.data[i] != ref.visibility.data[i];
  }
  std::printf("point light: %d covered, %d in shadow, %d differ\n", covered, shadowed, differ);
  EXPECT_GT(shadowed, covered / 20);
  EXPECT_LE(differ, covered / 500);
}

// No casters at all (only the ground): every covered pixel sees the light.
TEST_F(RaytracedRender, WithoutCastersEveryPixelSeesTheLight) {
  Scene s;
  s.name = "bare_ground";
  s.meshes.push_back(make_ground_plane("ground", {0.0f, 0.0f, 0.0f}, 6.0f));
  s.light.center = {0.0f, 4.0f, 0.0f};
  s.camera.eye = {0.0f, 5.0f, 5.0f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  ContractStage stage(s, kWidth, kHeight, {info_}, plugins_);
  const auto t = make(4);
  t->prepare(stage.inputs());
  const ImageF v = stage.render(*t);
  for (float x : v.data) ASSERT_EQ(x, 1.0f);
}

// A plate (a double-sided quad, x in [-1, 1], z in [-0.5, 0.5]) at height 2
// over the ground, under a 1×1 square light at height 4 facing down: a
// ground point p sees light point L blocked exactly when L lies in the
// plate scaled about p by 2, so V = 1 - (overlap of the light with that
// rectangle) / (light area), in closed form. Where that V is 0 or 1 every
// sample agrees and raytraced must give it exactly (a few pixels on the
// edges aside, where the G-buffer's rounded point decides); in the
// penumbra its error must look like noise of at most the binomial variance
// (2× it for a scrambled net, Owen 1997), with a mean of 0 in each quadrant.
// Light samples shifted by 1% of the light's side fail it (measured on
// llvmpipe: 4.6 to 6.8 standard errors in every quadrant).
TEST_F(RaytracedRender, PlateOverGroundMatchesItsClosedForm) {
  constexpr float kPlateHeight = 2.0f, kLightHeight = 4.0f;
  Scene s;
  s.name = "plate";
  s.meshes.push_back(make_ground_plane("ground", {0.0f, 0.0f, 0.0f}, 6.0f));
  core::Mesh plate;
  plate.name = "plate";
  plate.positions = {{-1.0f, kPlateHeight, -0.5f},
                     {1.0f, kPlateHeight, -0.5f},
                     {1.0f, kPlateHeight, 0.5f},
                     {-1.0f, kPlateHeight, 0.5f}};
  plate.normals.assign(4, glm::vec3(0.0f, 1.0f, 0.0f));
  plate.indices = {0, 2, 1, 0, 3, 2};
  plate.double_sided = true;
  s.meshes.push_back(plate);
  s.light.center = {0.0f, kLightHeight, 0.0f};
  s.light.half_u = {0.5f, 0.0f, 0.0f};
  s.light.half_v = {0.0f, 0.0f, 0.5f};
  s.light.target = {0.0f, 0.0f, 0.0f};
  s.camera.eye = {0.0f, 7.0f, 4.0f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.near_plane = 0.1f;
  s.camera.far_plane = 50.0f;
  constexpr int spp = 64;
  ContractStage stage(s, kWidth, kHeight, {info_}, plugins_);
  const auto t = make(spp);
  t->prepare(stage.inputs());
  const ImageF v = stage.render(*t);
  const std::vector<ImageF> g = stage.read_gbuffer();
  const auto overlap = [](double a0, double a1, double b0, double b1) {
    return std::max(0.0, std::min(a1, b1) - std::max(a0, b0));
  };
  const double k = kLightHeight / kPlateHeight;
  int ground = 0, hard = 0, hard_wrong = 0;
  // Per quadrant of the ground (sign of x, sign of z): a light sample off
  // to one side makes one side's penumbra darker and the other's lighter,
  // which a mean over the whole plate would cancel.
  int soft[4] = {0, 0, 0, 0};
  double sum[4] = {0, 0, 0, 0}, sum2[4] = {0, 0, 0, 0};
  for (size_t i = 0; i < v.pixel_count(); ++i) {
    const float* p = &g[0].data[i * 4];
    if (!(p[3] > 0.5f) || std::abs(p[1]) > 1e-4f) continue;  // the ground only
    ++ground;
    const double bx0 = p[0] + k * (-1.0 - p[0]), bx1 = p[0] + k * (1.0 - p[0]);
    const double bz0 = p[2] + k * (-0.5 - p[2]), bz1 = p[2] + k * (0.5 - p[2]);
    const double exact = 1.0 - overlap(-0.5, 0.5, bx0, bx1) * overlap(-0.5, 0.5, bz0, bz1);
    if (exact <= 1e-6 || exact >= 1.0 - 1e-6) {
      ++hard;
      hard_wrong += std::abs(v.data[i] - std::round(exact)) > 0.0;
      continue;
    }
    const int q = (p[0] > 0.0f ? 1 : 0) + (p[2] > 0.0f ? 2 : 0);
    ++soft[q];
    const double z = (v.data[i] - exact) / std::sqrt(exact * (1.0 - exact) / spp);
    sum[q] += z;
    sum2[q] += z * z;
  }
  std::printf("plate: %d ground pixels, %d hard (%d wrong)\n", ground, hard, hard_wrong);
  ASSERT_GT(hard, 1000);
  EXPECT_LE(hard_wrong, hard / 200);
  for (int q = 0; q < 4; ++q) {
    const double mean = sum[q] / std::max(soft[q], 1), mean2 = sum2[q] / std::max(soft[q], 1);
    const double se = std::sqrt(std::max(mean2 - mean * mean, 0.0) / std::max(soft[q] - 1, 1));
    std::printf("  quadrant %d: %d soft pixels, mean z %+.3f ± %.3f, mean z² %.3f\n", q, soft[q],
                mean, se, mean2);
    ASSERT_GT(soft[q], 100);
    EXPECT_LT(std::abs(mean), 4.0 * se) << "quadrant " << q;
    EXPECT_LT(mean2, 2.0) << "quadrant " << q;
  }
}

// The blue-noise shifts of one scrambled set keep every sample uniform.
TEST_F(RaytracedRender, SameExpectedVAsTheReferenceWithBlueNoiseShifts) {
  expect_same_expectation(sphere_grid(), 16, "sphere_grid_blue", "blue_noise");
  expect_same_expectation(scene_of("foliage", {{"trees", 2}}), 16, "foliage_blue", "blue_noise");
}

// The frame index scrambles the samples: with nothing moved, a second frame
// draws other points (the technique is temporal), and a technique prepared
// again draws the first frame's points again.
TEST_F(RaytracedRender, FramesDifferWithNothingMovedAndRepeatAfterPrepare) {
  ContractStage stage(sphere_grid(), kWidth, kHeight, {info_}, plugins_);
  const auto t = make(4);
  t->prepare(stage.inputs());
  const ImageF first = stage.render(*t);
  const ImageF second = stage.render(*t);
  t->prepare(stage.inputs());
  const ImageF again = stage.render(*t);
  EXPECT_GT(run::differing_pixels(first, second), size_t(100));
  EXPECT_EQ(run::differing_pixels(first, again), size_t(0));
  EXPECT_TRUE(info_->temporal);
}

// The hierarchy and the triangles are counted in technique.gpu_bytes: 48
// bytes a caster triangle, at least.
TEST_F(RaytracedRender, ItsBuffersAreCountedInGpuBytes) {
  const Scene s = sphere_grid();
  ContractStage stage(s, kWidth, kHeight, {info_}, plugins_);
  const auto t = make(4);
  gl::AllocationWindow meter;
  t->prepare(stage.inputs());
  EXPECT_GE(meter.peak_bytes(), std::int64_t(48 * s.caster_triangle_count()));
}

}  // namespace
}  // namespace sb::test
