#include "common/map_lookup.h"

#include "gl/debug.h"
#include "gl/objects.h"

namespace sb::shadow {
namespace {

const char* const kLookupHead = R"(#version 450 core
in vec2 uv;
layout(binding = 0) uniform sampler2D position_tex;
layout(binding = 1) uniform sampler2DShadow shadow_map;
layout(binding = 2) uniform sampler2D normal_tex;
uniform mat4 light_view_projection;
uniform vec3 light_point;
uniform float normal_offset;
uniform float weight;
out float visibility;
)";

const char* const kLookupMain = R"(
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 pos = texelFetch(position_tex, p, 0);
  if (pos.w == 0.0) { visibility = weight; return; }
  vec3 n = texelFetch(normal_tex, p, 0).xyz;
  vec3 t = light_coords(light_view_projection, offset_world(pos.xyz, n, light_point, normal_offset));
  visibility = weight * above_horizon(n, pos.xyz, light_point) * lit_fraction(t);
}
)";

}  // namespace

MapLookupPass::MapLookupPass(const std::string& name, const std::string& lit_fraction_glsl)
    : program_(name,
               {gl::kFullscreenVertexShader, "",
                std::string(kLookupHead) + kLightLookupGlsl + lit_fraction_glsl + kLookupMain}) {}

void MapLookupPass::draw(const FrameInputs& in, const LightFrustum& frustum,
                         const DepthMapSettings& settings, GLuint shadow_map, float weight) const {
  glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
  glViewport(0, 0, in.width, in.height);
  glDisable(GL_DEPTH_TEST);
  program_.use();
  program_.set("light_view_projection", frustum.view_projection);
  program_.set("light_point", frustum.eye);
  program_.set("normal_offset", settings.normal_offset_per_distance(frustum));
  program_.set("weight", weight);
  glBindTextureUnit(0, in.gbuffer_position);
  glBindTextureUnit(1, shadow_map);
  glBindTextureUnit(2, in.gbuffer_normal);
  gl::draw_fullscreen_triangle();
}

SingleMapTechnique::SingleMapTechnique(const Params& p, std::string name,
                                       std::string lit_fraction_glsl, bool linear_filtering)
    : name_(std::move(name)),
      lit_fraction_glsl_(std::move(lit_fraction_glsl)),
      linear_filtering_(linear_filtering),
      settings_(depth_map_settings(p)) {}

void SingleMapTechnique::prepare(const FrameInputs& in) {
  map_ = DepthMap(settings_.size, /*compare=*/true, linear_filtering_);
  frustum_ = fit_light_frustum(*in.scene, in.scene->light.center);
  lookup_ = MapLookupPass(name_ + "_lookup", lit_fraction_glsl_);
  set_uniforms(lookup_.program());
  gl::throw_if_errors(name_ + " prepare");
}

void SingleMapTechnique::render(const FrameInputs& in, gl::PassTimer& timer) {
  {
    auto pass = timer.scope("shadow_map");
    map_.render(*in.gpu, frustum_, settings_.cull, settings_.bias);
  }
  auto pass = timer.scope("lookup");
  lookup_.draw(in, frustum_, settings_, map_.texture());
}

}  // namespace sb::shadow
