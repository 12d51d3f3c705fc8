// penumbra_wedges — soft shadow volumes (Akenine-Möller & Assarsson 2002;
// Assarsson & Akenine-Möller 2003) for a rectangular area light:
//
//  1. umbra: stencil shadow volumes from the light's centre, through the
//     shared caster volumes (shadow_volume/caster_volumes.h) with every
//     silhouette mode of Mattausch et al. 2012; V = 1 − the count of
//     volumes around the point (0 in one umbra, 1 outside).
//  2. wedges: one per silhouette edge, the convex hull of every point whose
//     view of the light the edge can cut (wedge_geometry.h), built on the CPU
//     and drawn by its back faces, so each pixel is visited once per wedge
//     and surfaces behind the hull fail the depth test.
//  3. per fragment in a wedge (Lengyel's half-wedge test first): the edge,
//     cut at a local near plane just in front of the point p, is projected
//     from p onto the light's plane and its contribution added into a float
//     buffer: the area of the light in the sector from the light's centre
//     through the projected ends, beyond the projected edge, clipped
//     analytically to the light's rectangle (no lookup table). Summed over a
//     silhouette loop, these terms turn the centre's hard visibility into
//     1 − area(projected silhouette ∩ light) / area(light): the fan of the
//     projected loop about the centre, whose full sectors the umbra counted.
//  4. combine: V = clamp(umbra + Σ terms, 0, 1).
//
// Approximations of the method, measured in docs/penumbra_wedges.md: one
// silhouette, the light centre's, for every light point; overlapping
// silhouettes' occlusion is summed (over-darkening; clamped at 0), which is
// what penumbra_wedges_blend corrects. The umbra's count keeps that sum
// linear: with V = 0 for "in any umbra" instead, a point in two umbrae would
// get both silhouettes' lit parts added back, a light leak.
//
// Where the light's centre lies on a projected edge (p on that edge's hard
// shadow boundary), the sector is a half-plane on either side, and rounding
// decides which; where no volume holds the pixel, the term is taken on the
// side the stencil took (docs/penumbra_wedges.md).
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "gl/debug.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "penumbra_wedge/silhouette_wedges.h"
#include "penumbra_wedge/wedge_stream.h"
#include "penumbra_wedge/wedge_variants.h"
#include "plugin/registry.h"
#include "shadow_volume/caster_volumes.h"

namespace sb::techniques::penumbra_wedge {
namespace {

// The fragment's term: its edge's fan term over the light's area (kWedgeGlsl
// for the projection and clipping).
const char* const kWedgeMain = R"(
layout(binding = 0) uniform sampler2D position_tex;
layout(binding = 1) uniform sampler2D umbra_tex;  // 1 − the stencil's count: 1 outside every umbra
layout(binding = 2) uniform sampler2D owner_tex;  // Σ (number + 1) of the volumes holding the pixel
out float delta;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 pos = texelFetch(position_tex, pixel, 0);
  vec2 a, b;
  float s;
  if (pos.w == 0.0 || !fan_edge(pos.xyz, a, b, s)) discard;
  // Where the centre is on the edge, keep the side that agrees with the
  // stencil: where no volume holds the pixel every edge must darken (s < 0;
  // the term is s × an area); where one does, this edge must lighten if the
  // volume is its own silhouette's (the owner pass says whose), else darken.
  // Where two or more do, the shader keeps its own side.
  if (centre_on_edge(a, b)) {
    float umbra = texelFetch(umbra_tex, pixel, 0).r;  // 1 − count
    bool own = abs(texelFetch(owner_tex, pixel, 0).r - (wedges[v_wedge].a.w + 1.0)) < 0.5;
    if ((umbra > 0.5 && s > 0.0) || (umbra > -0.5 && umbra < 0.5 && (s > 0.0) != own))
      swap_ends(a, b, s);
  }
  float term = s * beyond_area(a, b);
  delta = term / (4.0 * half_size.x * half_size.y);
}
)";

// V from the stencil's count of the volumes around each pixel: 1 − count.
// Each silhouette whose volume holds the point adds its whole light, as
// its wedges add or remove parts of it: V = 1 − Σ occlusion, summed over
// silhouettes (the count is read through a stencil view of the G-buffer's
// depth-stencil texture; counts wrap in 8 bits).
const char* const kUmbraMain = R"(
layout(binding = 0) uniform sampler2D position_tex;
layout(binding = 1) uniform usampler2D stencil_tex;
out float visibility;
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  bool background = texelFetch(position_tex, pixel, 0).w == 0.0;
  visibility = background ? 1.0 : 1.0 - stencil_count(stencil_tex, pixel);
}
)";

// Which caster's volume holds a pixel: each volume adds ±(its number + 1)
// under the same rule the stencil counts by, so where one volume holds the
// pixel the sum is its number + 1.
const char* const kOwnerVertex = R"(#version 450 core
layout(location = 0) in vec4 position;
uniform mat4 view_projection;
void main() { gl_Position = view_projection * position; }
)";

const char* const kOwnerFragment = R"(#version 450 core
uniform float owner;       // the caster's number + 1
uniform float front_sign;  // z-fail: −1 (front faces behind the surface), z-pass: +1
out float owners;
void main() { owners = gl_FrontFacing ? front_sign * owner : -front_sign * owner; }
)";

const char* const kCombineFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D umbra_tex;
layout(binding = 1) uniform sampler2D delta_tex;
out float visibility;
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  visibility = clamp(texelFetch(umbra_tex, pixel, 0).r + texelFetch(delta_tex, pixel, 0).r, 0.0, 1.0);
}
)";

class PenumbraWedges final : public Technique {
 public:
  explicit PenumbraWedges(const Params& p) : offset_(p.get_float("offset")), wedges_(p) {}

  void prepare(const FrameInputs& in) override {
    wedges_.prepare(in);
    umbra_ = gl::Program("penumbra_wedges_umbra",
                         {gl::kFullscreenVertexShader, "",
                          std::string("#version 450 core\n") + kStencilCountGlsl + kUmbraMain});
    umbra_framebuffer_ = gl::make_framebuffer({in.visibility_texture}, 0);
    stencil_view_ = make_stencil_view(in.depth_stencil);
    wedge_program_ = gl::Program(
        "penumbra_wedges",
        {kWedgeVertex, "", std::string("#version 450 core\n") + kWedgeGlsl + kWedgeMain});
    combine_ =
        gl::Program("penumbra_wedges_combine", {gl::kFullscreenVertexShader, "", kCombineFragment});
    owner_program_ = gl::Program("penumbra_wedges_owners", {kOwnerVertex, "", kOwnerFragment});
    owners_ = gl::make_texture_2d(GL_R32F, in.width, in.height);
    owner_framebuffer_ =
        gl::make_framebuffer({owners_.get()}, in.depth_stencil, GL_DEPTH_STENCIL_ATTACHMENT);
    delta_ = gl::make_texture_2d(GL_R32F, in.width, in.height);
    delta_framebuffer_ =
        gl::make_framebuffer({delta_.get()}, in.depth_stencil, GL_DEPTH_STENCIL_ATTACHMENT);
    gl::throw_if_errors("penumbra_wedges prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    wedges_.build(in, timer);
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glViewport(0, 0, in.width, in.height);
    {
      auto pass = timer.scope("stencil");
      shadow_volume::begin_stencil_count(offset_);
      for (const bool zfail : {false, true}) {
        shadow_volume::set_stencil_ops(zfail);
        wedges_.volumes().draw(in, zfail);
      }
      shadow_volume::end_stencil_count();
    }
    {
      auto pass = timer.scope("owners");
      draw_owners(in);
    }
    {
      auto pass = timer.scope("umbra");
      glDisable(GL_STENCIL_TEST);
      glDisable(GL_DEPTH_TEST);
      glBindFramebuffer(GL_FRAMEBUFFER, umbra_framebuffer_.get());
      umbra_.use();
      glBindTextureUnit(0, in.gbuffer_position);
      glBindTextureUnit(1, stencil_view_.get());
      gl::draw_fullscreen_triangle();
      glBindTextureUnit(1, 0);
    }
    {
      auto pass = timer.scope("penumbra");
      glBindFramebuffer(GL_FRAMEBUFFER, delta_framebuffer_.get());
      const std::array<float, 4> zero{0.0f, 0.0f, 0.0f, 0.0f};
      glClearBufferfv(GL_COLOR, 0, zero.data());
      begin_hull_draw();
      glEnable(GL_BLEND);
      glBlendEquation(GL_FUNC_ADD);
      glBlendFunc(GL_ONE, GL_ONE);
      wedge_program_.use();
      set_wedge_uniforms(wedge_program_, wedges_.frame(), in.view_projection);
      glBindTextureUnit(0, in.gbuffer_position);
      glBindTextureUnit(1, in.visibility_texture);
      glBindTextureUnit(2, owners_.get());
      wedges_.stream().bind();
      WedgeStream::draw({0, uint32_t(wedges_.batch().indices.size())});
      glDisable(GL_BLEND);
      end_hull_draw();
    }
    auto pass = timer.scope("combine");
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glDepthMask(GL_TRUE);
    glTextureBarrier();  // each pixel reads its own umbra value, then writes V
    combine_.use();
    glBindTextureUnit(0, in.visibility_texture);
    glBindTextureUnit(1, delta_.get());
    gl::draw_fullscreen_triangle();
  }

 private:
  // The owners pass: every caster's volume, counted as the stencil counts
  // it, adds ±(its number + 1).
  void draw_owners(const FrameInputs& in) {
    glBindFramebuffer(GL_FRAMEBUFFER, owner_framebuffer_.get());
    const std::array<float, 4> zero{0.0f, 0.0f, 0.0f, 0.0f};
    glClearBufferfv(GL_COLOR, 0, zero.data());
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_DEPTH_CLAMP);
    glDisable(GL_CULL_FACE);
    if (offset_ != 0.0f) {
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(0.0f, offset_);
    }
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    owner_program_.set("view_projection", in.view_projection);
    const auto& casters = wedges_.volumes().casters();
    for (size_t i = 0; i < casters.size(); ++i) {
      // z-fail counts fragments that fail GL_LESS, z-pass those that pass.
      glDepthFunc(casters[i].zfail ? GL_GEQUAL : GL_LESS);
      owner_program_.set("owner", float(i + 1));
      owner_program_.set("front_sign", casters[i].zfail ? -1.0f : 1.0f);
      wedges_.volumes().draw_caster(in, i, &owner_program_);
    }
    glDisable(GL_BLEND);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_DEPTH_CLAMP);
    glDepthFunc(GL_LESS);
  }

  float offset_;
  SilhouetteWedges wedges_;
  gl::Program umbra_;
  gl::Program wedge_program_;
  gl::Program combine_;
  gl::Program owner_program_;
  gl::Texture owners_;  // Σ ±(number + 1) of the volumes around each pixel
  gl::Framebuffer owner_framebuffer_;
  gl::Texture delta_;
  gl::Framebuffer delta_framebuffer_;
  gl::Framebuffer umbra_framebuffer_;
  gl::Texture stencil_view_;  // the G-buffer's depth-stencil, read as stencil counts
};

}  // namespace

std::vector<ParamSpec> umbra_params() {
  std::vector<ParamSpec> params{
      choice_param("mode", "zfail", {"zpass", "zfail", "auto"},
                   "umbra volumes: zpass counts in front of the surface; zfail behind (robust); "
                   "auto uses zfail only for casters whose volume can reach the camera's near "
                   "plane"),
      float_param("offset", 1.0, -1e6, 1e6,
                  "glPolygonOffset units pushing umbra volume faces away from the camera")};
  for (ParamSpec& spec : shadow_volume::silhouette_params(
           "the light centre's silhouette (shadow_volume's modes, Mattausch et al. 2012); the "
           "wedges follow the same loops"))
    params.push_back(std::move(spec));
  return params;
}

TechniqueInfo penumbra_wedges_info() {
  return {
      .name = "penumbra_wedges",
      .family = "penumbra_wedge",
      .summary =
          "soft shadow volumes (Akenine-Möller & Assarsson 2002): an umbra from the light centre's "
          "shadow volumes, then one wedge per silhouette edge whose fragments add the light area "
          "that the edge, projected from the point, uncovers or covers (analytic clipping to the "
          "rectangle)",
      .needs = Needs{need::kRectangularLight, need::kClosedCasters, need::kOpaqueCasters,
                     need::kCasterEdges},
      .params = umbra_params(),
      .create = [](const Params& p) { return std::make_unique<PenumbraWedges>(p); }};
}

}  // namespace sb::techniques::penumbra_wedge
