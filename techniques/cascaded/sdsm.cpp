// sdsm — sample distribution shadow maps (Lauritzen, Salvi, Lefohn 2011):
// cascaded shadow maps for the sun whose partitions are placed where the
// frame's pixels are. Each frame a GPU reduction over the G-buffer gives the
// covered pixels' min and max view depth; the partitions split that range
// (logarithmically by default, the paper's scheme), not the camera's near
// and far; with `bounds: tight` (the paper's full method) a second reduction
// gives each partition's pixels' box in the sun's frame, and the partition's
// ortho box is fitted to it (extended towards the sun to the casters).
//
// Every frame (render(), timed as "reduction", then "shadow_map", then
// "lookup"): the reductions and their read-backs (2 floats, then 6 per
// partition), the boxes on the CPU, the N depth passes, one full-screen
// lookup (the cascaded family's, cascade_lookup_glsl.h).
//
// Parameters, defaults and ranges: docs/parameters.md; the technique and the
// paper: docs/sun.md.
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
#include "cascaded/sample_reduction.h"
#include "common/glsl_pcf.h"
#include "gl/debug.h"
#include "gl/glsl_pieces.h"

namespace sb::techniques::cascaded {
namespace {

using core::choice_param;
using core::float_param;
using core::int_param;
using core::odd;
using core::Params;
using core::ParamSpec;
using plugin::FrameInputs;
using plugin::TechniqueInfo;

constexpr int kMaxPartitions = SampleReduction::kMaxPartitions;
// A pixel whose depth is this close (relative) to a partition's end counts in
// both partitions' bounds: the lookup computes its depth in its own rounding.
constexpr float kSeam = 1e-5f;

class SampleDistributionShadowMap final : public plugin::Technique {
 public:
  explicit SampleDistributionShadowMap(const Params& p)
      : settings_(depth_map_settings(p)),
        partitions_(p.get_int("cascades")),
        lambda_(p.get_float("lambda")),
        tight_(p.get_string("bounds") == "tight"),
        blend_band_(p.get_float("blend_band")),
        filter_(p.get_string("filter") == "hard"  ? 0
                : p.get_string("filter") == "pcf" ? 1
                                                  : 2),
        filter_radius_(p.get_int("filter_taps") / 2),
        search_radius_(p.get_int("search_taps") / 2),
        min_filter_texels_(p.get_float("min_filter_texels")),
        output_(p.get_string("output")) {}

  void prepare(const FrameInputs& in) override {
    // Fixed scene data (neither the light's nor the camera's): derived once.
    const core::Bounds casters = in.scene->caster_bounds();
    caster_corners_ = box_corners(casters.lo, casters.hi);
    reduction_ = SampleReduction(true);
    maps_ = CascadeDepthArray(settings_.size, partitions_, settings_.depth_format);
    lookup_ = gl::Program("sdsm_lookup",
                          {gl::kFullscreenVertexShader, "",
                           std::string(kCascadeInputsGlsl) + kPcfGlsl + kCascadeLookupGlsl});
    compare_sampler_ = gl::make_sampler(filter_ != 0, /*compare=*/true, /*border=*/1.0f);
    raw_sampler_ = gl::make_sampler(/*linear=*/false, /*compare=*/false, /*border=*/1.0f);
    lookup_.set("cascade_count", partitions_);
    lookup_.set("filter_mode", filter_);
    lookup_.set_if_active("filter_radius", filter_radius_);
    lookup_.set_if_active("search_radius", search_radius_);
    lookup_.set_if_active("min_filter_texels", min_filter_texels_);
    lookup_.set_if_active("normal_offset", settings_.normal_offset);
    lookup_.set("show_cascades", output_ == "cascade" ? 1 : 0);
    lookup_.set("show_texels", output_ == "texel" ? 1 : 0);
    gl::throw_if_errors("sdsm prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    const core::AreaLight& light = in.scene->light;
    const glm::mat4& P = in.projection;
    const CameraFrustum camera{in.view, 1.0f / P[1][1], P[1][1] / P[0][0]};
    CascadePlan plan;
    std::vector<LightBounds> bounds;
    {
      auto pass = timer.scope("reduction");
      glm::vec2 range = reduction_.depth_range(in.gbuffer_position, in.width, in.height, in.view);
      if (range.x > range.y) {
        // Nothing covered: nothing to shadow; any range will do.
        const float near_plane = P[3][2] / (P[2][2] - 1.0f);
        range = {near_plane, 2.0f * near_plane};
      }
      // A range of one depth (a wall facing the camera) still needs ordered splits.
      range.y = std::max(range.y, range.x * (1.0f + 1e-4f));
      plan.splits = practical_splits(range.x, range.y, partitions_, lambda_);
      for (int i = 0; i < partitions_; ++i)
        plan.bands.push_back(i + 1 < partitions_ ? blend_band_ * (plan.splits[size_t(i) + 1] -
                                                                  plan.splits[size_t(i)])
                                                 : 0.0f);
      if (tight_)
        bounds = reduction_.light_bounds(
            in.gbuffer_position, in.width, in.height, in.view, light_rotation(light.direction()),
            std::vector<float>(plan.splits.begin() + 1, plan.splits.end()), plan.bands, kSeam);
    }
    {
      auto pass = timer.scope("shadow_map");
      // Filter taps, the texel's bilinear neighbour and the normal offset
      // read around a sample: the tight box keeps that many texels around them.
      const float pad = float(std::max(filter_radius_, filter_ == 2 ? search_radius_ : 0)) + 2.0f +
                        settings_.normal_offset;
      for (int i = 0; i < partitions_; ++i) {
        const float d0 = plan.splits[size_t(i)], d1 = plan.splits[size_t(i) + 1];
        const float start = i > 0 ? std::max(d0 - plan.bands[size_t(i) - 1], plan.splits[0]) : d0;
        const bool empty = tight_ && bounds[size_t(i)].empty();
        plan.boxes.push_back(tight_ && !empty
                                 ? fit_light_bounds(bounds[size_t(i)].lo, bounds[size_t(i)].hi,
                                                    light.direction(), caster_corners_,
                                                    settings_.size, pad)
                                 : fit_cascade(camera, start, d1, light.direction(),
                                               caster_corners_, settings_.size, FitMode::Tight));
        // No pixel reads an empty partition's map.
        if (!empty)
          maps_.render(*in.gpu, i, plan.boxes.back().view_projection, settings_.cull,
                       settings_.bias);
      }
    }
    auto pass = timer.scope("lookup");
    draw_cascade_lookup(lookup_, plan, in, light, maps_.texture(), compare_sampler_.get(),
                        raw_sampler_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
  }

 private:
  DepthMapSettings settings_;
  int partitions_;
  float lambda_;
  bool tight_;
  float blend_band_;
  int filter_;
  int filter_radius_;
  int search_radius_;
  float min_filter_texels_;
  std::string output_;
  std::array<glm::vec3, 8> caster_corners_{};
  SampleReduction reduction_;
  CascadeDepthArray maps_;
  gl::Program lookup_;
  gl::Sampler compare_sampler_;
  gl::Sampler raw_sampler_;
};

}  // namespace

TechniqueInfo sdsm_info() {
  std::vector<ParamSpec> params = {
      int_param("cascades", 4, 1, kMaxPartitions,
                "partitions N: the covered pixels' depth range [z_min, z_max] split in N, one "
                "map each"),
      float_param("lambda", 1.0, 0.0, 1.0,
                  "partition scheme over [z_min, z_max]: 1 logarithmic (the paper's), below 1 "
                  "the practical scheme's blend with uniform (Zhang et al. 2006), 0 uniform"),
      choice_param("bounds", "tight", {"tight", "depth"},
                   "tight (the paper's full method): each partition's box fitted to its pixels' "
                   "light-space bounds (a second GPU reduction); depth (its basic variant): "
                   "only z_min/z_max, each box fitted to its frustum slice's corners"),
      float_param("blend_band", 0.0, 0.0, 0.5,
                  "fraction of each partition's depth range blended into the next; 0 (the "
                  "paper's): hard seams"),
      choice_param("filter", "pcf", {"hard", "pcf", "pcss"},
                   "per-partition lookup: one comparison, a PCF grid, or PCSS with the sun's "
                   "penumbra (d_receiver - d_blocker)·2·tan(angular diameter / 2)"),
      odd(int_param("filter_taps", 3, 1, 31,
                    "PCF grid SIDE (odd), not a tap count: side² bilinear taps (pcf: one texel "
                    "apart; pcss: spread over the penumbra)")),
      odd(int_param("search_taps", 5, 1, 31,
                    "pcss blocker-search grid SIDE (odd), not a tap count: side² taps")),
      float_param("min_filter_texels", 1.0, 0.0, 64.0,
                  "pcss: smallest PCF radius (half its width), in texels"),
      choice_param("output", "visibility", {"visibility", "cascade", "texel"},
                   "cascade: write the partition index (0 first .. 1 last, blended in the "
                   "bands) instead of V; texel: the world size of the pixel's partition's texel "
                   "(its box's larger side / size); neither is a shadow")};
  for (auto& p : depth_map_params(2048)) {
    if (p.name == "size") p.doc = "each partition's map side in texels (the array holds N of them)";
    params.push_back(std::move(p));
  }
  return {
      .name = "sdsm",
      .family = "cascaded",
      .summary =
          "sample distribution shadow maps (Lauritzen et al. 2011): partitions over "
          "the covered pixels' depth range, reduced on the GPU each frame, with tight "
          "light-space bounds per partition; hard/PCF/PCSS lookups",
      .needs = Needs{need::kSunLight, need::kCasterClosedness},
      .params = std::move(params),
      .create = [](const Params& p) { return std::make_unique<SampleDistributionShadowMap>(p); }};
}

}  // namespace sb::techniques::cascaded
