// heidrich_linear — soft shadow maps for linear lights (Heidrich, Brabec &
// Seidel 2000; Rahman 2007 §3.2): hard depth maps from the segment's two
// ends. Each map's depth discontinuities become "skin" quads
// (shadow_map/linear_light_skins.h) that are rendered, Gouraud-shaded from
// 0 on the occluder to 1 on the receiver, from the other end into that end's
// visibility map.
//
// The lookup tests a point against both maps: seen from both ends it is
// lit (V = 1), from neither it is in umbra (V = 0), and from one end only
// it reads that end's visibility map, bilinearly: the skin of the other end's
// shadow boundary lies between this end and the point, and its shade there
// is the lit fraction of the segment. Overlapping skins keep the darkest
// shade (min blending): occluders that hide the segment from the same end
// hide nested intervals, and the larger one is the answer. Where the
// point's tangent plane cuts the segment, the part above it is computed
// exactly (the skins only describe other occluders).
//
// What it cannot see, as published: a point lit only from the segment's
// middle (an occluder smaller than the penumbra) is in umbra; a texel no
// skin reached reads `lit` (0.5 by default, as the survey says).
// docs/linear_lights.md has the measurements.
//
// Passes: shadow_maps (both ends), read_back (to the CPU), skins (the
// quads, on the CPU), upload, visibility_maps (the skins from the other
// end), lookup.
//
// Parameters, defaults and ranges: docs/parameters.md.
#include <algorithm>
#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "common/depth_cliffs.h"
#include "common/depth_pass.h"
#include "common/map_lookup.h"
#include "gl/debug.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "shadow_map/linear_light_skins.h"
#include "shadow_map/shadow_map_variants.h"

namespace sb::techniques::shadow_map {
namespace {

const char* const kSkinVertex = R"(#version 450 core
layout(location = 0) in vec4 position;
layout(location = 1) in float skin_visibility;
uniform mat4 light_view_projection;
// Screen-space interpolation, as Gouraud shading was: for a receiver plane
// parallel to the light it gives the segment's lit fraction exactly
// (linear_light_skins.h), where a perspective-correct one would not.
noperspective out float shade;
void main() {
  shade = skin_visibility;
  gl_Position = light_view_projection * position;
}
)";

const char* const kSkinFragment = R"(#version 450 core
noperspective in float shade;
out float visibility;
// Clamped: the rasteriser may overshoot a vertex value by a rounding error.
void main() { visibility = clamp(shade, 0.0, 1.0); }
)";

// The lookup: this head, common/depth_pass.h's light helpers, the body.
const char* const kLookupHead = R"(#version 450 core
in vec2 uv;
layout(binding = 0) uniform sampler2D position_tex;
layout(binding = 1) uniform sampler2DShadow map_a;
layout(binding = 2) uniform sampler2D normal_tex;
layout(binding = 3) uniform sampler2DShadow map_b;
layout(binding = 4) uniform sampler2D visibility_a;
layout(binding = 5) uniform sampler2D visibility_b;
uniform mat4 view_projection_a, view_projection_b;
uniform mat4 view_a, view_b;
uniform vec3 end_a, end_b;
uniform float normal_offset_a, normal_offset_b;
uniform float lit;
out float visibility;
)";

const char* const kLookupBody = R"(
// Whether the light's end sees `world` past the casters (1) or not (0),
// and where the point falls in that end's maps. Behind the end's eye plane
// or outside its map's cone nothing stands between (the cone holds every
// caster).
float seen(mat4 view_projection, mat4 view, sampler2DShadow map, vec3 end, float normal_offset,
           vec3 world, vec3 n, out vec3 t) {
  t = vec3(-1.0);
  vec3 p = offset_world(world, n, end, normal_offset);
  if ((view_projection * vec4(p, 1.0)).w <= 0.0 || (view * vec4(p, 1.0)).z >= 0.0) return 1.0;
  t = light_coords(view_projection, p);
  if (any(lessThan(t.xy, vec2(0.0))) || any(greaterThan(t.xy, vec2(1.0)))) return 1.0;
  return texture(map, t);
}

// The visibility map's shade at t: bilinear between texel centres over the
// texels a skin reached (cleared to kNoSkin: a clear value of `lit` would
// cap every shade at it under min blending), so that a skin's end does not
// fade into the default; where none of the four was reached, the nearest
// one that was within two texels, else `lit`; `lit` outside the map.
float shade(sampler2D map, vec3 t) {
  if (any(lessThan(t.xy, vec2(0.0))) || any(greaterThan(t.xy, vec2(1.0)))) return lit;
  ivec2 size = textureSize(map, 0);
  vec2 x = t.xy * vec2(size) - 0.5;
  ivec2 base = ivec2(floor(x));
  vec2 f = x - vec2(base);
  float sum = 0.0, weight = 0.0;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      ivec2 texel = clamp(base + ivec2(i, j), ivec2(0), size - 1);
      float v = texelFetch(map, texel, 0).r;
      float w = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y);
      if (v <= 1.0) {
        sum += w * v;
        weight += w;
      }
    }
  }
  if (weight > 0.0) return sum / weight;
  // A hole: the nearest texel a skin reached within two texels. A skin's
  // ends are quantised to the other map's texels, so a sliver beside the
  // occluder's edge (or the receiver's) can stay uncovered; the skin next
  // to it holds the right end's shade (0 at the occluder, 1 at the receiver).
  float nearest = 1e9, value = lit;
  for (int j = -1; j <= 2; ++j) {
    for (int i = -1; i <= 2; ++i) {
      ivec2 texel = base + ivec2(i, j);
      if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, size))) continue;
      float v = texelFetch(map, texel, 0).r;
      vec2 d = vec2(texel) - x;
      if (v <= 1.0 && dot(d, d) < nearest) {
        nearest = dot(d, d);
        value = v;
      }
    }
  }
  return value;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 pos = texelFetch(position_tex, pixel, 0);
  if (pos.w == 0.0) { visibility = 1.0; return; }
  vec3 n = texelFetch(normal_tex, pixel, 0).xyz;
  vec3 ta, tb;
  float a = seen(view_projection_a, view_a, map_a, end_a, normal_offset_a, pos.xyz, n, ta);
  float b = seen(view_projection_b, view_b, map_b, end_b, normal_offset_b, pos.xyz, n, tb);
  // The surface's own horizon, exactly: the part of the segment above the
  // tangent plane (linear along it). The skins describe other occluders'
  // shadows only; where the plane cuts the segment, the end above it says
  // whether a caster hides that part too.
  float ha = dot(n, end_a - pos.xyz), hb = dot(n, end_b - pos.xyz);
  if (ha <= 0.0 && hb <= 0.0) {
    visibility = 0.0;
  } else if (ha <= 0.0 || hb <= 0.0) {
    visibility = (ha > 0.0 ? a : b) * max(ha, hb) / (abs(ha) + abs(hb));
  } else if (a > 0.5 && b > 0.5) {
    visibility = 1.0;
  } else if (a <= 0.5 && b <= 0.5) {
    visibility = 0.0;
  } else {
    visibility = b > 0.5 ? shade(visibility_b, tb) : shade(visibility_a, ta);
  }
}
)";

// A visibility map's texels that no skin reached (shades are in [0, 1]).
constexpr float kNoSkin = 2.0f;

// One end of the segment: its depth map, the map read back, its skin and
// its visibility map (drawn over the map's depth, so a skin counts only in
// front of what the end sees).
struct End {
  LightFrustum frustum;
  DepthMap map;
  std::vector<float> depths;
  std::vector<SkinVertex> skin;
  gl::Buffer skin_buffer;
  gl::VertexArray skin_vao;
  gl::Texture visibility;
  gl::Framebuffer visibility_framebuffer;
};

class HeidrichLinear final : public Technique {
 public:
  explicit HeidrichLinear(const Params& p)
      : settings_(depth_map_settings(p)),
        threshold_(p.get_float("edge_threshold")),
        lit_(p.get_float("lit")) {}

  void prepare(const FrameInputs& in) override {
    bounds_ = in.scene->bounds();  // the scene's, not the light's: immutable
    const int size = settings_.size;
    for (End& e : ends_) {
      e.map = DepthMap(size, settings_.depth_format);
      e.depths.assign(size_t(size) * size_t(size), 1.0f);
      e.visibility = gl::make_texture_2d(GL_R16F, size, size);
      e.visibility_framebuffer = gl::make_framebuffer({e.visibility.get()}, e.map.texture());
      e.skin_buffer = gl::make_stream_buffer();
      const GLuint buffer = e.skin_buffer.get();
      GLuint vao = 0;
      glCreateVertexArrays(1, &vao);
      e.skin_vao = gl::VertexArray(vao);
      glVertexArrayVertexBuffer(vao, 0, buffer, 0, sizeof(SkinVertex));
      glEnableVertexArrayAttrib(vao, 0);
      glVertexArrayAttribFormat(vao, 0, 4, GL_FLOAT, GL_FALSE, offsetof(SkinVertex, position));
      glVertexArrayAttribBinding(vao, 0, 0);
      glEnableVertexArrayAttrib(vao, 1);
      glVertexArrayAttribFormat(vao, 1, 1, GL_FLOAT, GL_FALSE, offsetof(SkinVertex, visibility));
      glVertexArrayAttribBinding(vao, 1, 0);
    }
    skin_program_ = gl::Program("heidrich_linear_skin", {kSkinVertex, "", kSkinFragment});
    lookup_ = gl::Program("heidrich_linear_lookup",
                          {gl::kFullscreenVertexShader, "",
                           std::string(kLookupHead) + kLightLookupGlsl + kLookupBody});
    lookup_.set("lit", lit_);
    compare_sampler_ = gl::make_sampler(/*linear=*/false, /*compare=*/true, /*border=*/1.0f);
    gl::throw_if_errors("heidrich_linear prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    const AreaLight& light = in.scene->light;
    {
      auto pass = timer.scope("shadow_maps");
      for (size_t i = 0; i < 2; ++i) {
        End& e = ends_[i];
        // Widened by the rest of the light: the other end's shadow, which
        // this end's visibility map must hold, lies inside.
        e.frustum = fit_light_frustum(*in.scene, light.segment_end(float(i)));
        // The receivers too: a skin ends on the receiver behind the
        // occluder, and is tested against what this end sees.
        e.map.render(*in.gpu, e.frustum, settings_.cull, settings_.bias, /*receivers_too=*/true);
      }
    }
    {
      auto pass = timer.scope("read_back");
      for (End& e : ends_)
        glGetTextureImage(e.map.texture(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                          GLsizei(e.depths.size() * sizeof(float)), e.depths.data());
    }
    {
      auto pass = timer.scope("skins");
      for (End& e : ends_) {
        e.skin.clear();
        append_linear_light_skins(e.depths, settings_.size, e.frustum, threshold_,
                                  past_every_receiver(bounds_, e.frustum.eye), e.skin);
      }
    }
    {
      auto pass = timer.scope("upload");
      for (End& e : ends_)
        gl::set_buffer_data(e.skin_buffer, GLsizeiptr(e.skin.size() * sizeof(SkinVertex)),
                            e.skin.data(), GL_STREAM_DRAW);
    }
    {
      auto pass = timer.scope("visibility_maps");
      glViewport(0, 0, settings_.size, settings_.size);
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LESS);
      glDepthMask(GL_FALSE);
      glDisable(GL_CULL_FACE);
      glEnable(GL_BLEND);
      glBlendEquation(GL_MIN);
      skin_program_.use();
      for (size_t i = 0; i < 2; ++i) {
        End& e = ends_[i];
        const End& other = ends_[1 - i];
        glBindFramebuffer(GL_FRAMEBUFFER, e.visibility_framebuffer.get());
        glClearNamedFramebufferfv(e.visibility_framebuffer.get(), GL_COLOR, 0,
                                  std::array<float, 4>{kNoSkin, 0.0f, 0.0f, 0.0f}.data());
        if (other.skin.empty()) continue;
        skin_program_.set("light_view_projection", e.frustum.view_projection);
        glBindVertexArray(other.skin_vao.get());
        glDrawArrays(GL_TRIANGLES, 0, GLsizei(other.skin.size()));
      }
      glBlendEquation(GL_FUNC_ADD);
      glDisable(GL_BLEND);
      glDepthMask(GL_TRUE);
      glDisable(GL_DEPTH_TEST);
    }
    auto pass = timer.scope("lookup");
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glViewport(0, 0, in.width, in.height);
    lookup_.use();
    const End &a = ends_[0], &b = ends_[1];
    lookup_.set("view_projection_a", a.frustum.view_projection);
    lookup_.set("view_projection_b", b.frustum.view_projection);
    lookup_.set_if_active("view_a", a.frustum.view);
    lookup_.set_if_active("view_b", b.frustum.view);
    lookup_.set("end_a", a.frustum.eye);
    lookup_.set("end_b", b.frustum.eye);
    lookup_.set_if_active("normal_offset_a", settings_.normal_offset_per_distance(a.frustum));
    lookup_.set_if_active("normal_offset_b", settings_.normal_offset_per_distance(b.frustum));
    glBindTextureUnit(0, in.gbuffer_position);
    glBindTextureUnit(1, a.map.texture());
    glBindSampler(1, compare_sampler_.get());
    glBindTextureUnit(2, in.gbuffer_normal);
    glBindTextureUnit(3, b.map.texture());
    glBindSampler(3, compare_sampler_.get());
    glBindTextureUnit(4, a.visibility.get());
    glBindTextureUnit(5, b.visibility.get());
    gl::draw_fullscreen_triangle();
    glBindSampler(1, 0);
    glBindSampler(3, 0);
  }

 private:
  DepthMapSettings settings_;
  float threshold_;
  float lit_;
  Bounds bounds_;
  std::array<End, 2> ends_;
  gl::Program skin_program_, lookup_;
  gl::Sampler compare_sampler_;
};

}  // namespace

TechniqueInfo heidrich_linear_info() {
  std::vector<ParamSpec> params = depth_map_params(1024, "front");
  params.push_back(float_param("edge_threshold", 0.002, 0.0, 10.0,
                               "a step between neighbouring texels is a discontinuity (a skin "
                               "quad) when it, and its distance from each side's linear "
                               "extrapolation, exceed this fraction of the nearer depth"));
  params.push_back(float_param("lit", 0.5, 0.0, 1.0,
                               "visibility of a point seen from one end only where no skin "
                               "falls (the visibility maps' clear value; 0.5 as in the survey)"));
  return {.name = "heidrich_linear",
          .family = "shadow_map",
          .summary =
              "soft shadow maps for linear lights: depth maps at the segment's ends, their "
              "discontinuities' skins Gouraud-shaded from the other end into visibility maps "
              "(Heidrich, Brabec & Seidel 2000)",
          .needs =  // Closedness decides which casters `cull` may cull: asked for
          // always, so that the maps do not depend on what else the plan runs.
          Needs{need::kLinearLight, need::kCasterClosedness},
          .params = std::move(params),
          .create = [](const Params& p) { return std::make_unique<HeidrichLinear>(p); }};
}

}  // namespace sb::techniques::shadow_map
