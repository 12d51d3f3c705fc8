// occlusion_textures — plausible soft shadows from prefiltered occlusion
// textures (Eisemann & Décoret 2008). Per frame:
//   "slices":  the casters' depth range from the light is cut into slabs
//              (slicing.h), and the casters are drawn once into one binary
//              texture per slab, four slabs per RGBA8 target (slab_rasterizer.h);
//   "filter":  each texture's prefiltered form is built (filter_pyramid.h:
//              mipmap, N-buffers or a summed-area table);
//   "lookup":  every G-buffer point p reads, from each slab between it and
//              the light, the texture's mean over the light rectangle seen
//              from p through one plane of the slab (lookup_plane: its
//              middle, or its far side as the paper has it; one box
//              lookup per slab),
//              and combines the slabs' occlusions α_k:
//                probabilistic  V = Π (1 − α_k)   (independent slabs, eq. 5)
//                sum            V = max(0, 1 − Σ α_k)
//                max            V = 1 − max α_k
// Every caster is in the slabs and every point is shaded from those in
// front of it. A point skips self_shadow_offset slabs towards the light,
// fading the next one in (slicing.h), which keeps lit surfaces from
// shadowing themselves. The paper does so for every point, with no
// caster/receiver separation (self_slab=skip). The default,
// self_slab=receiver_aware, lets a point on a mesh that casts nothing (the
// harness's one definition of V leaves it out of every caster pass) read
// up to its own depth instead: measured better (docs/occlusion_textures.md).
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <memory>
#include <string>
#include <vector>

#include "gl/debug.h"
#include "gl/gpu_scene.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "occlusion_texture/filter_pyramid.h"
#include "occlusion_texture/occlusion_variants.h"
#include "occlusion_texture/slab_rasterizer.h"
#include "occlusion_texture/slicing.h"

namespace sb::techniques::occlusion_texture {
namespace {

enum class Combine { Probabilistic, Sum, Max };

Combine combine_from_string(const std::string& s) {
  if (s == "sum") return Combine::Sum;
  if (s == "max") return Combine::Max;
  return Combine::Probabilistic;
}

const char* const kLookupHead = R"(
in vec2 uv;
layout(binding = 0) uniform sampler2D position_tex;
layout(binding = 2) uniform sampler2D normal_tex;
uniform int size;
uniform float caster_offset;    // slabs a caster's own point skips (self_shadow_offset)
uniform float receiver_offset;  // the same for a point that casts nothing (self_slab)
uniform float plane_fraction;   // 1: the counted part's far side; 0.5: its middle
out float visibility;
)";

// The occlusion of slab k's texture over the texel box [lo, hi]: its mean
// over the part inside the texture, times that part's share of the box (the
// light beyond the texture is unoccluded). A box of no area (a light of no
// area, or the point on the slab's plane) reads the texel under its centre.
const char* const kLookupMain = R"(
float slab_occlusion(int k, vec2 lo, vec2 hi) {
  int t = k / 4, c = k % 4;
  vec2 side = hi - lo;
  float area = side.x * side.y;
  if (!(area > 1e-6)) {
    vec2 centre = 0.5 * (lo + hi);
    if (any(lessThan(centre, vec2(0.0))) || any(greaterThanEqual(centre, vec2(size)))) return 0.0;
    return source_texel(t, ivec2(centre))[c];
  }
  vec2 inside_lo = clamp(lo, vec2(0.0), vec2(size)), inside_hi = clamp(hi, vec2(0.0), vec2(size));
  vec2 inside = inside_hi - inside_lo;
  if (!(inside.x > 0.0 && inside.y > 0.0)) return 0.0;
  return box_mean(t, inside_lo, inside_hi)[c] * (inside.x * inside.y / area);
}
// clamp(v, 0, 1) that lets NaN and Inf through to the harness's finiteness check.
float clamp_unit(float v) { return (isnan(v) || isinf(v)) ? v : clamp(v, 0.0, 1.0); }
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 pos = texelFetch(position_tex, p, 0);
  if (pos.w == 0.0) { visibility = 1.0; return; }
  vec4 normal = texelFetch(normal_tex, p, 0);
  float horizon = dot(normal.xyz, light_center - pos.xyz) > 0.0 ? 1.0 : 0.0;
  vec3 l = to_light(pos.xyz);
  // A caster's own surface is in the slabs; a receiver that casts nothing is not.
  float offset = normal.w > 0.5 ? caster_offset : receiver_offset;
  float lit = 1.0, total = 0.0, strongest = 0.0;
  for (int k = 0; k < SLABS; ++k) {
    // The part of slab k in front of l.z − offset (slicing.h). Slabs lie in
    // depth order: once one has no such part, none after it has.
    float near_side = z0 + float(k) * thickness;
    float top = min(near_side + thickness, l.z - offset * thickness);
    if (!(top > near_side)) break;
    float w = (top - near_side) / thickness;
    float zk = near_side + plane_fraction * (top - near_side);
    float r = zk / l.z;
    vec2 centre = l.xy * r;
    vec2 half_size = light_half * (1.0 - r);
    vec2 to_texels = scale / (proj_a * zk + proj_b) * float(size);
    vec2 lo = (centre - half_size - origin) * to_texels + 0.5 * float(size);
    vec2 hi = (centre + half_size - origin) * to_texels + 0.5 * float(size);
    float occlusion = w * slab_occlusion(k, lo, hi);
    lit *= 1.0 - occlusion;
    total += occlusion;
    strongest = max(strongest, occlusion);
  }
#if COMBINE == 0
  float v = lit;
#elif COMBINE == 1
  float v = 1.0 - total;
#else
  float v = 1.0 - strongest;
#endif
  visibility = horizon * clamp_unit(v);
}
)";

std::string lookup_fragment(int slabs, int textures, Filter filter, Combine combine) {
  return "#version 450 core\n#define SLABS " + std::to_string(slabs) + "\n#define TEXTURES " +
         std::to_string(textures) + "\n#define COMBINE " + std::to_string(int(combine)) + "\n" +
         kSlicingUniformsGlsl + kLookupHead + box_mean_glsl(filter) + kLookupMain;
}

class OcclusionTextures final : public Technique {
 public:
  explicit OcclusionTextures(const Params& p)
      : slabs_(p.get_int("slices")),
        size_(p.get_int("size")),
        filter_(filter_from_string(p.get_string("filter"))),
        sat_half_(p.get_string("sat_precision") == "16"),
        combine_(combine_from_string(p.get_string("combine"))),
        projection_(projection_from_string(p.get_string("projection"))),
        light_facing_only_(p.get_string("faces") == "light_facing"),
        thin_occluder_fix_(p.get_bool("thin_occluder_fix")),
        self_slab_(self_slab_from_string(p.get_string("self_slab"))),
        lookup_plane_(lookup_plane_from_string(p.get_string("lookup_plane"))),
        self_shadow_offset_(p.get_float("self_shadow_offset")) {}

  void prepare(const FrameInputs& /*in*/) override {
    const int textures = (slabs_ + 3) / 4;
    pyramids_.clear();
    std::vector<GLuint> targets;
    for (int t = 0; t < textures; ++t) {
      pyramids_.push_back(std::make_unique<FilterPyramid>(filter_, size_, sat_half_));
      targets.push_back(pyramids_.back()->source());
    }
    rasterizer_ = SlabRasterizer(slabs_, size_, targets, light_facing_only_, thin_occluder_fix_);
    lookup_ = gl::Program(
        "occlusion_lookup",
        {gl::kFullscreenVertexShader, "", lookup_fragment(slabs_, textures, filter_, combine_)});
    lookup_.set("size", size_);
    lookup_.set("caster_offset", self_shadow_offset_);
    lookup_.set("receiver_offset",
                point_offset(self_slab_, /*casts_shadow=*/false, self_shadow_offset_));
    lookup_.set("plane_fraction", plane_fraction(lookup_plane_));
    gl::throw_if_errors("occlusion_textures: prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    Slicing slicing;
    {
      auto pass = timer.scope("slices");
      slicing = fit_slicing(*in.scene, slabs_, projection_);
      rasterizer_.render(*in.gpu, slicing);
    }
    {
      auto pass = timer.scope("filter");
      for (const auto& pyramid : pyramids_) pyramid->build();
    }
    auto pass = timer.scope("lookup");
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glViewport(0, 0, in.width, in.height);
    glDisable(GL_DEPTH_TEST);
    lookup_.use();
    set_slicing_uniforms(lookup_, slicing);
    lookup_.set("light_half", glm::vec2(slicing.light.half_width, slicing.light.half_height));
    glBindTextureUnit(0, in.gbuffer_position);
    glBindTextureUnit(2, in.gbuffer_normal);
    for (size_t t = 0; t < pyramids_.size(); ++t)
      pyramids_[t]->bind_for_lookup(GLuint(kFirstLookupUnit) + GLuint(t));
    gl::draw_fullscreen_triangle();
  }

 private:
  int slabs_;
  int size_;
  Filter filter_;
  bool sat_half_;
  Combine combine_;
  Projection projection_;
  bool light_facing_only_;
  bool thin_occluder_fix_;
  SelfSlab self_slab_;
  LookupPlane lookup_plane_;
  float self_shadow_offset_;
  std::vector<std::unique_ptr<FilterPyramid>> pyramids_;
  SlabRasterizer rasterizer_;
  gl::Program lookup_;
};

ParamSpec power_of_two(ParamSpec spec) {
  spec.rule = [](const nlohmann::json& v) {
    const int n = v.get<int>();
    return (n > 0 && (n & (n - 1)) == 0) ? std::string() : std::string("a power of two");
  };
  spec.rule_doc = "power of two";
  return spec;
}

ParamSpec slab_count(ParamSpec spec) {
  spec.rule = [](const nlohmann::json& v) {
    const int n = v.get<int>();
    return (n == 4 || n == 8 || n == 16) ? std::string() : std::string("4, 8 or 16");
  };
  spec.rule_doc = "4, 8 or 16";
  return spec;
}

}  // namespace

TechniqueInfo occlusion_textures_info() {
  return {
      .name = "occlusion_textures",
      .family = "occlusion_texture",
      .summary =
          "prefiltered occlusion textures of light-parallel slices, combined as independent "
          "probabilities (Eisemann & Decoret 2008)",
      .needs = Needs{need::kRectangularLight, need::kCasterClosedness},
      .params =
          {slab_count(int_param("slices", 16, 4, 16,
                                "slices between the light and the scene, four per RGBA texture")),
           power_of_two(int_param("size", 512, 16, 4096, "occlusion texture side in texels")),
           choice_param("filter", "sat", {"mipmap", "nbuffers", "sat"},
                        "prefiltering: mip chain (trilinear), N-buffers, or summed-area table"),
           choice_param("sat_precision", "32", {"32", "16"},
                        "float bits of the summed-area table (16 shows the loss)"),
           choice_param("combine", "probabilistic", {"probabilistic", "sum", "max"},
                        "how slices' occlusions combine: product of (1 - a), sum, or largest"),
           choice_param(
               "projection", "central", {"central", "orthographic"},
               "slices projected from a centre behind the light whose frustum fits the light, "
               "or along the light's normal"),
           choice_param("faces", "light_facing", {"light_facing", "all"},
                        "faces of closed casters drawn into the slices (open ones draw all)"),
           float_param(
               "self_shadow_offset", 1.0, 0.0, 4.0,
               "slices a point skips towards the light before the slices it reads (the slice "
               "holding it, and the fade of the one in front)"),
           choice_param(
               "self_slab", "receiver_aware", {"receiver_aware", "skip"},
               "who skips self_shadow_offset slices: every point (paper), or casters only, "
               "receivers that cast nothing reading their own slice up to their depth"),
           choice_param(
               "lookup_plane", "mid", {"mid", "far"},
               "plane each slice is read through: its middle, or its far side from the light "
               "(paper)"),
           bool_param("thin_occluder_fix", false,
                      "also mark each slice's occluders in the next slice away from the light (the "
                      "paper's fix for light leaking between slices)")},
      .create = [](const Params& p) { return std::make_unique<OcclusionTextures>(p); }};
}

}  // namespace sb::techniques::occlusion_texture
