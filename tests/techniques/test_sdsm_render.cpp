// sdsm (sample distribution shadow maps, Lauritzen et al. 2011) on a small
// sun scene built here whose geometry ends far short of the camera's far
// plane (a street 40 units long, far plane 400): its partitions' texels
// against cascaded_shadow_map's for the same view, its hard V against the
// analytic shadow (a ground point is shadowed exactly when its ray towards
// the sun hits a box), its GPU reduction against a CPU min/max over the
// same G-buffer, the timing contract under a turning sun, and its GPU
// memory (drives Mesa).
//
// With SB_SDSM_IMAGES=<folder> set, the tests write what they render there
// as PGM images for a person to look at.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <string>

#include "cascaded/sample_reduction.h"
#include "core/scene_types.h"
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
using techniques::cascaded::LightBounds;
using techniques::cascaded::SampleReduction;
using techniques::cascaded::view_depth;

constexpr int kWidth = 320;
constexpr int kHeight = 240;
// The near pixels: from the nearest (about 3.7) to 8 units away.
constexpr float kNear = 8.0f;

struct Box {
  glm::vec3 center, half;
};
const Box kBoxes[] = {{{-1.0f, 0.6f, 1.0f}, {0.5f, 0.6f, 0.5f}},
                      {{1.5f, 1.0f, -3.0f}, {0.7f, 1.0f, 0.7f}},
                      {{-2.5f, 1.5f, -12.0f}, {1.0f, 1.5f, 1.0f}},
                      {{3.0f, 2.0f, -22.0f}, {1.4f, 2.0f, 1.4f}},
                      {{-4.0f, 2.5f, -30.0f}, {1.8f, 2.5f, 1.8f}}};
const glm::vec3 kToSun = glm::normalize(glm::vec3(0.9f, 0.8f, 0.3f));

// A street 50 units long (z from 15 to -35), the camera in it 2 units over
// the ground, looking down along it: the nearest pixels are about 3.7 units
// away, the farthest about 43; the near plane is at 0.1 (the street goes on
// behind the camera: the scene's box does not narrow it), the far plane at
// 400, eight times the street.
Scene street_scene() {
  Scene s;
  s.name = "sdsm_street";
  s.meshes.push_back(make_ground_plane("ground", {0.0f, 0.0f, -10.0f}, 25.0f));
  for (size_t i = 0; i < std::size(kBoxes); ++i)
    s.meshes.push_back(make_box("box" + std::to_string(i), kBoxes[i].center, kBoxes[i].half));
  s.light = core::make_sun_light(kToSun, {0.0f, 0.0f, -15.0f}, 1e-4f, 80.0f);
  s.camera.eye = {0.0f, 2.0f, 8.0f};
  s.camera.target = {0.0f, 0.0f, -20.0f};
  s.camera.fov_y_degrees = 50.0f;
  s.camera.near_plane = 0.1f;
  s.camera.far_plane = 400.0f;
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

void maybe_write(const ImageF& img, const std::string& name, float scale = 1.0f) {
  const char* dir = std::getenv("SB_SDSM_IMAGES");
  if (!dir) return;
  std::ofstream f(std::string(dir) + "/" + name + ".pgm", std::ios::binary);
  f << "P5\n" << img.width << " " << img.height << "\n255\n";
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      f.put(char(std::clamp(int(std::lround(255.0f * scale * img.at(x, y))), 0, 255)));
}

class SdsmRender : public ::testing::Test {
 protected:
  void SetUp() override {
    plugins_.load_plugins(SHADOWBENCH_PLUGIN_DIR);
    context_ = gl::create_context(gl::Backend::OSMesa);
    sdsm_ = plugins_.find("sdsm");
    csm_ = plugins_.find("cascaded_shadow_map");
    ASSERT_NE(sdsm_, nullptr);
    ASSERT_NE(csm_, nullptr);
    stage_ = std::make_unique<ContractStage>(street_scene(), kWidth, kHeight,
                                             std::vector{sdsm_, csm_}, plugins_);
    ASSERT_EQ(stage_->skip_reason(0), "");
    ASSERT_EQ(stage_->skip_reason(1), "");
  }
  Params params(const TechniqueInfo* info, nlohmann::json p) const {
    if (!p.contains("size")) p["size"] = 256;
    return resolve_params(info->params, p, "", "");
  }
  ImageF render(const TechniqueInfo* info, const nlohmann::json& p) {
    const auto t = info->create(params(info, p));
    t->prepare(stage_->inputs());
    return stage_->render(*t);
  }

  // How a technique's variant does on the street's covered pixels.
  struct Outcome {
    double mean_texel = 0.0;  // world size of the texels the pixels read, mean
    double near_texel = 0.0;  // the same over the pixels nearer than kNear
    int wrong = 0;            // ground pixels whose hard V is not the analytic one
    int compared = 0;
  };
  Outcome outcome(const TechniqueInfo* info, nlohmann::json p, const std::string& name) {
    p["filter"] = "hard";
    const ImageF v = render(info, p);
    p["output"] = "texel";
    const ImageF texel = render(info, p);
    p["output"] = "cascade";
    const ImageF cascade = render(info, p);
    maybe_write(v, name + "_v");
    maybe_write(cascade, name + "_cascade");
    maybe_write(texel, name + "_texel", 10.0f);
    const ImageF position = stage_->read_gbuffer()[0];
    const ImageF normal = stage_->read_gbuffer()[1];
    Outcome o;
    int covered = 0, near = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        if (position.at(x, y, 3) == 0.0f) continue;
        ++covered;
        o.mean_texel += texel.at(x, y);
        const glm::vec3 p3{position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2)};
        if (view_depth(stage_->inputs().view, p3) < kNear) {
          ++near;
          o.near_texel += texel.at(x, y);
        }
        if (normal.at(x, y, 1) < 0.99f || std::abs(p3.y) > 1e-3f) continue;  // the ground only
        ++o.compared;
        o.wrong += std::abs(v.at(x, y) - (shadowed(p3) ? 0.0f : 1.0f)) > 0.5f;
      }
    o.mean_texel /= std::max(covered, 1);
    o.near_texel /= std::max(near, 1);
    std::printf("%-24s texel: mean %.4f, nearer than %g %.4f; %d of %d ground pixels wrong\n",
                name.c_str(), o.mean_texel, double(kNear), o.near_texel, o.wrong, o.compared);
    return o;
  }

  Registry plugins_;
  std::unique_ptr<gl::Context> context_;
  const TechniqueInfo* sdsm_ = nullptr;
  const TechniqueInfo* csm_ = nullptr;
  std::unique_ptr<ContractStage> stage_;
};

// The case: SDSM's bounds tighter than PSSM's where the far range is
// empty. Against the cascaded maps at their defaults (practical splits of
// the camera's range narrowed to the scene's box, stable spheres), SDSM at
// its defaults reads texels under 0.6× as large, on the near pixels and over
// the image, and gets a third fewer ground pixels' hard shadow wrong
// (measured on llvmpipe: 0.45× and 0.47×, 34 pixels against 98).
TEST_F(SdsmRender, ItsBoundsAreTighterThanTheCascadesWhereTheFarRangeIsEmpty) {
  const Outcome csm = outcome(csm_, {}, "csm_defaults");
  const Outcome sdsm = outcome(sdsm_, {}, "sdsm_defaults");
  ASSERT_GT(sdsm.compared, kWidth * kHeight / 3);
  EXPECT_LT(sdsm.near_texel, 0.6 * csm.near_texel);
  EXPECT_LT(sdsm.mean_texel, 0.6 * csm.mean_texel);
  EXPECT_LT(sdsm.wrong, csm.wrong * 2 / 3);
}

// The reduction is what places the partitions: with the same scheme and
// fit as the cascades (logarithmic, each box its slice's corners, no
// bands), SDSM's `depth` bounds differ from the cascades' only by the range
// they split, the covered pixels' [z_min, z_max] against the camera's
// [near, far] narrowed to the scene's box (which reaches behind the camera).
// Replaced by the camera's range, the texels would be equal and this fails
// (measured: 0.80× on the near pixels, 0.63× over the image, 59 wrong
// pixels against 112).
TEST_F(SdsmRender, TheDepthReductionAloneShrinksTheTexels) {
  const Outcome csm = outcome(csm_, {{"lambda", 1.0}, {"stable", false}, {"blend_band", 0.0}},
                              "csm_logarithmic_tight");
  const Outcome depth = outcome(sdsm_, {{"bounds", "depth"}}, "sdsm_depth_bounds");
  EXPECT_LT(depth.near_texel, 0.9 * csm.near_texel);
  EXPECT_LT(depth.mean_texel, 0.75 * csm.mean_texel);
  EXPECT_LT(depth.wrong, csm.wrong * 3 / 4);
}

// The tight light-space bounds (the paper's full method) against the depth
// bounds only: each partition's box is fitted to its pixels, not to its
// frustum slice (which holds the sky and the street's sides): smaller
// texels, fewer wrong pixels. Without the second reduction the two are the
// same and this fails (measured: 0.52× both, 34 wrong pixels against 59).
TEST_F(SdsmRender, TightLightSpaceBoundsShrinkTheTexels) {
  const Outcome depth = outcome(sdsm_, {{"bounds", "depth"}}, "sdsm_depth_bounds");
  const Outcome tight = outcome(sdsm_, {{"bounds", "tight"}}, "sdsm_tight_bounds");
  EXPECT_LT(tight.near_texel, 0.75 * depth.near_texel);
  EXPECT_LT(tight.mean_texel, 0.75 * depth.mean_texel);
  EXPECT_LT(tight.wrong, depth.wrong);
}

// The GPU reduction against the CPU's over the same G-buffer: the min and
// max view depth are the same floats (both compute each depth in the same
// order, unfused), and each partition's light-space box is the CPU's to
// float rounding (the light transform's order is the GL's).
TEST_F(SdsmRender, ItsReductionsAgreeWithTheCpusOverTheSameGbuffer) {
  const plugin::FrameInputs& in = stage_->inputs();
  const ImageF position = stage_->read_gbuffer()[0];
  float lo = 1e30f, hi = -1e30f;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      if (position.at(x, y, 3) != 0.0f) {
        const float d =
            view_depth(in.view, {position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2)});
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
  SampleReduction reduction(true);
  const glm::vec2 gpu = reduction.depth_range(in.gbuffer_position, kWidth, kHeight, in.view);
  EXPECT_EQ(gpu.x, lo);
  EXPECT_EQ(gpu.y, hi);
  EXPECT_GT(lo, 2.0f);   // the street's nearest pixel, not the near plane
  EXPECT_LT(hi, 50.0f);  // its farthest, not the far plane

  // Three partitions, the second with a blend band reaching into the first's.
  const std::vector<float> ends = {8.0f, 20.0f, 1e30f}, bands = {2.0f, 0.0f, 0.0f};
  const glm::mat4 light_view = glm::lookAt(glm::vec3(0.0f), -kToSun, glm::vec3(0, 1, 0));
  const std::vector<LightBounds> got = reduction.light_bounds(
      in.gbuffer_position, kWidth, kHeight, in.view, light_view, ends, bands, 0.0f);
  std::vector<LightBounds> want(3, {glm::vec3(1e30f), glm::vec3(-1e30f)});
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (position.at(x, y, 3) == 0.0f) continue;
      const glm::vec3 p{position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2)};
      const float d = view_depth(in.view, p);
      const glm::vec4 l = light_view * glm::vec4(p, 1.0f);
      const glm::vec3 q{l.x, l.y, -l.z};
      const int i = d > ends[0] ? (d > ends[1] ? 2 : 1) : 0;
      const auto add = [&](int k) {
        want[size_t(k)].lo = glm::min(want[size_t(k)].lo, q);
        want[size_t(k)].hi = glm::max(want[size_t(k)].hi, q);
      };
      add(i);
      if (i == 0 && d > ends[0] - bands[0]) add(1);
    }
  ASSERT_EQ(got.size(), 3u);
  for (size_t i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      const float tol = 1e-5f * (1.0f + std::abs(want[i].hi[k]) + std::abs(want[i].lo[k]));
      EXPECT_NEAR(got[i].lo[k], want[i].lo[k], tol) << "partition " << i << " axis " << k;
      EXPECT_NEAR(got[i].hi[k], want[i].hi[k], tol) << "partition " << i << " axis " << k;
    }
  // The band's pixels widened the second partition towards the camera.
  EXPECT_LT(got[1].lo.z, got[1].hi.z);
}

// The timing contract under the sun: check-technique's checks, with the
// sun turned by about 10 degrees between prepare() and a frame.
TEST_F(SdsmRender, KeepsTheTimingContractUnderTheSun) {
  stage_ = std::make_unique<ContractStage>(street_scene(), 96, 72, std::vector{sdsm_}, plugins_);
  const core::AreaLight first = stage_->scene().light;
  for (const char* bounds : {"tight", "depth"})
    for (const char* filter : {"hard", "pcss"}) {
      const Params p = params(sdsm_, {{"filter", filter}, {"bounds", bounds}, {"blend_band", 0.2}});
      const auto create = [&] { return sdsm_->create(p); };
      const core::AreaLight second =
          core::make_sun_light(glm::normalize(kToSun + glm::vec3(-0.2f, 0.0f, 0.1f)), first.target,
                               first.angular_diameter, 80.0f);
      const ContractStage::Frames f = stage_->across_a_move(
          create, [&] { stage_->set_light(first); }, [&] { stage_->set_light(second); });
      stage_->set_light(first);
      EXPECT_EQ(run::differing_pixels(f.a_moved, f.b_moved), 0u) << bounds << " " << filter;
      EXPECT_GT(run::differing_pixels(f.a_first, f.a_moved), 0u) << bounds << " " << filter;
      for (const run::ContractCheck& c : {run::check_camera_move(*stage_, create, true),
                                          run::check_visibility_written(*stage_, create),
                                          run::check_deterministic(*stage_, create),
                                          run::check_gbuffer_untouched(*stage_, create)})
        EXPECT_TRUE(c.passed()) << bounds << " " << filter << ": " << c.name << ": " << c.failure;
    }
}

// Its maps are an array of `cascades` layers of size² 32-bit depths, and the
// reductions' buffer: technique.gpu_bytes counts them.
TEST_F(SdsmRender, ItsGpuMemoryIsItsPartitionsDepthMapsAndTheReductionsBuffer) {
  const gl::AllocationWindow window;
  const auto t = sdsm_->create(params(sdsm_, {{"cascades", 3}, {"size", 512}}));
  t->prepare(stage_->inputs());
  EXPECT_EQ(window.live_bytes(), std::int64_t(3) * 512 * 512 * 4 + SampleReduction::kBufferBytes);
}

}  // namespace
}  // namespace sb::test
