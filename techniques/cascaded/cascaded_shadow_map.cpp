// cascaded_shadow_map — cascaded shadow maps for the sun (Engel 2006) with
// the practical split scheme of parallel-split shadow maps (Zhang et al.
// 2006), stable cascades (Valient 2008) and blend bands between cascades:
// the camera's depth range split into N slices, each shadowed by an
// orthographic map from the sun fitted to it, every pixel looked up in the
// cascade its view depth falls in.
//
// Every frame (render(), timed as "shadow_map"): the splits, the boxes and
// the N depth passes; then "lookup": one full-screen pass.
//
// Parameters, defaults and ranges: docs/parameters.md; the technique and the
// papers: docs/sun.md.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>

#include "cascaded/cascade_depth_array.h"
#include "cascaded/cascade_fit.h"
#include "cascaded/cascade_lookup_glsl.h"
#include "cascaded/cascade_lookup_pass.h"
#include "cascaded/cascaded_variants.h"
#include "common/glsl_pcf.h"
#include "gl/debug.h"
#include "gl/glsl_pieces.h"

namespace sb::techniques::cascaded {
namespace {

using core::bool_param;
using core::choice_param;
using core::float_param;
using core::int_param;
using core::odd;
using core::Params;
using core::ParamSpec;
using plugin::FrameInputs;
using plugin::TechniqueInfo;

constexpr int kMaxCascades = 8;

int filter_mode(const std::string& filter) {
  return filter == "hard" ? 0 : filter == "pcf" ? 1 : 2;
}

// The camera's depth range that holds the scene: its clip planes, narrowed
// to the scene's bounding box (a far plane far behind the scene would spend
// the splits on empty space).
glm::vec2 scene_depth_range(const FrameInputs& in, const core::Bounds& b, float near_plane,
                            float far_plane) {
  float lo = far_plane, hi = near_plane;
  for (const glm::vec3& p : box_corners(b.lo, b.hi)) {
    const float d = -(in.view * glm::vec4(p, 1.0f)).z;
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  const float n = std::max(near_plane, lo), f = std::min(far_plane, hi);
  return f > n ? glm::vec2(n, f) : glm::vec2(near_plane, far_plane);
}

class CascadedShadowMap final : public plugin::Technique {
 public:
  explicit CascadedShadowMap(const Params& p)
      : settings_(depth_map_settings(p)),
        cascades_(p.get_int("cascades")),
        lambda_(p.get_float("lambda")),
        mode_(p.get_bool("stable") ? FitMode::Stable : FitMode::Tight),
        blend_band_(p.get_float("blend_band")),
        filter_(filter_mode(p.get_string("filter"))),
        filter_radius_(p.get_int("filter_taps") / 2),
        search_radius_(p.get_int("search_taps") / 2),
        min_filter_texels_(p.get_float("min_filter_texels")),
        show_cascades_(p.get_string("output") == "cascade"),
        show_texels_(p.get_string("output") == "texel") {}

  void prepare(const FrameInputs& in) override {
    // Fixed scene data (neither the light's nor the camera's): derived once.
    scene_bounds_ = in.scene->bounds();
    const core::Bounds casters = in.scene->caster_bounds();
    caster_corners_ = box_corners(casters.lo, casters.hi);
    maps_ = CascadeDepthArray(settings_.size, cascades_, settings_.depth_format);
    lookup_ = gl::Program("cascaded_shadow_map_lookup",
                          {gl::kFullscreenVertexShader, "",
                           std::string(kCascadeInputsGlsl) + kPcfGlsl + kCascadeLookupGlsl});
    // A filter's hardware 2×2 comparison for pcf and pcss, one texel for hard.
    compare_sampler_ = gl::make_sampler(filter_ != 0, /*compare=*/true, /*border=*/1.0f);
    raw_sampler_ = gl::make_sampler(/*linear=*/false, /*compare=*/false, /*border=*/1.0f);
    lookup_.set("cascade_count", cascades_);
    lookup_.set("filter_mode", filter_);
    lookup_.set_if_active("filter_radius", filter_radius_);
    lookup_.set_if_active("search_radius", search_radius_);
    lookup_.set_if_active("min_filter_texels", min_filter_texels_);
    lookup_.set_if_active("normal_offset", settings_.normal_offset);
    lookup_.set("show_cascades", show_cascades_ ? 1 : 0);
    lookup_.set("show_texels", show_texels_ ? 1 : 0);
    gl::throw_if_errors("cascaded_shadow_map prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    const core::AreaLight& light = in.scene->light;
    CascadePlan plan;
    {
      auto pass = timer.scope("shadow_map");
      // The camera as the projection has it (glm::perspective).
      const glm::mat4& P = in.projection;
      CameraFrustum camera{in.view, 1.0f / P[1][1], P[1][1] / P[0][0]};
      const float near_plane = P[3][2] / (P[2][2] - 1.0f);
      const float far_plane = P[3][2] / (P[2][2] + 1.0f);
      const glm::vec2 range = scene_depth_range(in, scene_bounds_, near_plane, far_plane);
      plan = plan_cascades(camera, range.x, range.y, cascades_, lambda_, blend_band_,
                           light.direction(), caster_corners_, settings_.size, mode_);
      for (int i = 0; i < cascades_; ++i)
        maps_.render(*in.gpu, i, plan.boxes[size_t(i)].view_projection, settings_.cull,
                     settings_.bias);
    }
    auto pass = timer.scope("lookup");
    draw_cascade_lookup(lookup_, plan, in, light, maps_.texture(), compare_sampler_.get(),
                        raw_sampler_.get());
  }

 private:
  DepthMapSettings settings_;
  int cascades_;
  float lambda_;
  FitMode mode_;
  float blend_band_;
  int filter_;
  int filter_radius_;
  int search_radius_;
  float min_filter_texels_;
  bool show_cascades_;
  bool show_texels_;
  core::Bounds scene_bounds_;
  std::array<glm::vec3, 8> caster_corners_{};
  CascadeDepthArray maps_;
  gl::Program lookup_;
  gl::Sampler compare_sampler_;
  gl::Sampler raw_sampler_;
};

}  // namespace

TechniqueInfo cascaded_shadow_map_info() {
  std::vector<ParamSpec> params = {
      int_param("cascades", 4, 1, kMaxCascades,
                "cascades N: the camera's depth range split in N slices, one map each"),
      float_param("lambda", 0.5, 0.0, 1.0,
                  "practical split scheme's blend (Zhang et al. 2006): 1 logarithmic, 0 uniform"),
      bool_param("stable", true,
                 "stable cascades (Valient 2008): each box fits its slice's bounding sphere, "
                 "snapped to whole texels; false: the slice's tight box, which shimmers"),
      float_param("blend_band", 0.1, 0.0, 0.5,
                  "fraction of each cascade's depth range blended into the next; 0: hard seams"),
      choice_param("filter", "pcf", {"hard", "pcf", "pcss"},
                   "per-cascade lookup: one comparison, a PCF grid, or PCSS with the sun's "
                   "penumbra (d_receiver - d_blocker)·2·tan(angular diameter / 2)"),
      odd(int_param("filter_taps", 3, 1, 31,
                    "PCF grid SIDE (odd), not a tap count: side² bilinear taps (pcf: one texel "
                    "apart; pcss: spread over the penumbra)")),
      odd(int_param("search_taps", 5, 1, 31,
                    "pcss blocker-search grid SIDE (odd), not a tap count: side² taps")),
      float_param("min_filter_texels", 1.0, 0.0, 64.0,
                  "pcss: smallest PCF radius (half its width), in texels"),
      choice_param("output", "visibility", {"visibility", "cascade", "texel"},
                   "cascade: write the cascade index (0 first .. 1 last, blended in the bands) "
                   "instead of V, to look at the splits; texel: the world size of the pixel's "
                   "cascade's texel (its box's larger side / size); neither is a shadow")};
  // The size is each cascade's: a cascade is as large as another technique's one map.
  for (auto& p : depth_map_params(2048)) {
    if (p.name == "size") p.doc = "each cascade's map side in texels (the array holds N of them)";
    params.push_back(std::move(p));
  }
  return {.name = "cascaded_shadow_map",
          .family = "cascaded",
          .summary =
              "cascaded shadow maps for the sun: practical splits (Zhang et al. 2006), "
              "stable cascades (Valient 2008), blend bands, hard/PCF/PCSS lookups",
          .needs = Needs{need::kSunLight, need::kCasterClosedness},
          .params = std::move(params),
          .create = [](const Params& p) { return std::make_unique<CascadedShadowMap>(p); }};
}

}  // namespace sb::techniques::cascaded
