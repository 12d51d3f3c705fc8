// raytraced — stochastic ray-traced soft shadows, the baseline of soft-shadow
// papers since hardware ray tracing (e.g. Boksansky, Wimmer & Bittner 2019,
// "Ray traced shadows: maintaining real-time frame rates", Ray Tracing
// Gems ch. 13; Heitz, Hill & McGuire 2018, "Combining analytic direct
// illumination and stochastic shadows"), on GL 4.5 compute shaders:
//   prepare()  a binned-SAH hierarchy over the caster triangles (Wald 2007;
//              shadow_bvh.h), uploaded with the alpha masks (gpu_casters.h);
//   render()   one compute pass, one invocation per G-buffer pixel: `spp`
//              shadow rays from the surface point, offset by the reference's
//              rule (reference/ray_offset.h), to points of the light drawn as
//              the reference draws them (reference/pixel_rays.cpp), any-hit
//              traversal with a watertight triangle test (Woop, Benthin &
//              Wald 2013) and masks sampled as core::sample_alpha does.
// The points: Owen-scrambled 2-D Sobol (Burley 2020, "Practical Hash-based
// Owen Scrambling", JCGT 9(4)), scrambled per pixel and per frame: frame k
// since prepare() draws other points than frame k - 1 (TechniqueInfo::
// temporal), so a denoiser or temporal filter can gather them. Or
// (`sequence: blue_noise`) one scrambled set per frame for every pixel,
// shifted toroidally per pixel by two void-and-cluster masks
// (common/blue_noise.h), blue-noise dithered sampling after Georgiev &
// Fajardo 2016: each shifted point of a scrambled set is still uniform, so
// the estimate stays unbiased, and its error is spread as blue noise.
//
// With `denoiser: svgf` the rays' V goes into a texture of its own and the
// kit's spatiotemporal denoiser (common/visibility_denoiser.h; Schied et al.
// 2017, with a neighbourhood clamp against a moving light's ghosts) filters
// it into the visibility target, its passes timed in the same frame.
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "common/blue_noise.h"
#include "common/visibility_denoiser.h"
#include "gl/debug.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "plugin/registry.h"
#include "raytraced/gpu_casters.h"
#include "raytraced/raytraced_glsl.h"

namespace sb::techniques::raytraced {
namespace {

class Raytraced final : public Technique {
 public:
  explicit Raytraced(const Params& p)
      : spp_(p.get_int("spp")),
        leaf_size_(p.get_int("leaf_size")),
        sequence_(p.get_string("sequence")),
        seed_(uint64_t(p.get_int("seed"))),
        denoiser_settings_(denoiser_settings(p)) {}

  void prepare(const FrameInputs& in) override {
    casters_ = GpuCasters(*in.scene, leaf_size_);
    const std::string source = std::string("#version 450 core\n") + kRaytracedInputsGlsl +
                               kSobolGlsl + kRayOffsetGlsl + kTraversalGlsl + kBlueNoiseGlsl +
                               kRaytracedMainGlsl;
    program_ = gl::Program::compute("raytraced", source);
    program_.set("spp", spp_);
    program_.set("has_casters", casters_.empty() ? 0 : 1);
    program_.set("blue", sequence_ == "blue_noise" ? 1 : 0);
    if (sequence_ == "blue_noise") {
      // Masks of the parameters alone: two independent ones, one a coordinate.
      blue_x_ = make_blue_noise_texture(kBlueNoiseSide, unsigned(seed_));
      blue_y_ = make_blue_noise_texture(kBlueNoiseSide, unsigned(seed_) + 0x9e3779b9u);
    }
    frame_ = 0;
    if (denoiser_settings_) {
      noisy_ = gl::make_texture_2d(GL_R32F, in.width, in.height);
      denoiser_.emplace(*denoiser_settings_);
      denoiser_->prepare(in.width, in.height);
    }
    gl::throw_if_errors("raytraced prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    trace(in, timer);
    if (denoiser_) denoiser_->denoise(in, noisy_.get(), timer);
  }

 private:
  void trace(const FrameInputs& in, gl::PassTimer& timer) {
    auto pass = timer.scope("trace");
    ++frame_;
    const AreaLight& l = in.scene->light;
    program_.set("size", glm::ivec2(in.width, in.height));
    glProgramUniform1ui(program_.id(), program_.location("frame_seed"),
                        GLuint(core::splitmix64(seed_, frame_)));
    program_.set("sun", l.is_sun() ? 1 : 0);
    program_.set("light_center", l.center);
    // The reference's own expressions (reference/pixel_rays.cpp: RaySetup).
    program_.set("corner", l.center - l.half_u - l.half_v);
    program_.set("eu", 2.0f * l.half_u);
    program_.set("ev", 2.0f * l.half_v);
    program_.set("axis", l.to_sun());
    program_.set("e1",
                 glm::length(l.half_u) > 0.0f ? glm::normalize(l.half_u) : glm::vec3(1, 0, 0));
    program_.set("e2",
                 glm::length(l.half_v) > 0.0f ? glm::normalize(l.half_v) : glm::vec3(0, 0, 1));
    program_.set("tan_radius", std::tan(0.5f * l.angular_diameter));
    program_.use();
    casters_.bind();
    glBindTextureUnit(0, in.gbuffer_position);
    glBindTextureUnit(1, in.gbuffer_normal);
    if (blue_x_) {
      glBindTextureUnit(4, blue_x_.get());
      glBindTextureUnit(5, blue_y_.get());
    }
    glBindImageTexture(0, denoiser_ ? noisy_.get() : in.visibility_texture, 0, GL_FALSE, 0,
                       GL_WRITE_ONLY, GL_R32F);
    glDispatchCompute(GLuint((in.width + 7) / 8), GLuint((in.height + 7) / 8), 1);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  }

  int spp_;
  int leaf_size_;
  std::string sequence_;
  uint64_t seed_;
  uint64_t frame_ = 0;  // render() calls since prepare()
  GpuCasters casters_;
  gl::Program program_;
  static constexpr int kBlueNoiseSide = 64;
  gl::Texture blue_x_, blue_y_;  // sequence "blue_noise" only
  std::optional<DenoiserSettings> denoiser_settings_;
  // With a denoiser: the rays' V, and the filter that writes the target.
  gl::Texture noisy_;
  std::optional<VisibilityDenoiser> denoiser_;
};

}  // namespace
}  // namespace sb::techniques::raytraced

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  using namespace sb;
  std::vector<core::ParamSpec> params = {
      int_param("spp", 4, 1, 64, "shadow rays per pixel and frame"),
      int_param("leaf_size", 4, 1, 16, "most triangles in a leaf of the hierarchy"),
      choice_param("sequence", "sobol", {"sobol", "blue_noise"},
                   "light samples: Owen-scrambled Sobol (Burley 2020), scrambled per "
                   "pixel and frame; blue_noise: one scrambled set per frame, shifted "
                   "per pixel by two 64² blue-noise masks (Georgiev & Fajardo 2016)"),
      int_param("seed", 1, 0, 2147483647, "scrambling seed")};
  for (core::ParamSpec& p : techniques::denoiser_params("none")) params.push_back(std::move(p));
  registry.add(
      {.name = "raytraced",
       .family = "raytraced",
       .summary = "N shadow rays per pixel to Owen-scrambled Sobol points on the light, through a "
                  "BVH of the casters on the GPU (compute shader)",
       .needs = Needs{need::kSunOrLocalLight},
       .params = std::move(params),
       .create =
           [](const Params& p) { return std::make_unique<techniques::raytraced::Raytraced>(p); },
       // Jobs of 1, 4 and 16 spp took 2.2-2.4×, 4.8-6.2× and 17-21× a 1024² hard
       // shadow map's at 320×240 on the sphere grid and foliage (loaded 2-core
       // VM, llvmpipe): about 1 + 1.1 spp.
       .cost_weight = [](const Params& p) { return 1.0 + 1.1 * p.get_int("spp"); },
       .temporal = true});
}
