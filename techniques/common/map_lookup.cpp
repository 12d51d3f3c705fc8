#include "common/map_lookup.h"

#include "common/map_lookup_glsl.h"
#include "gl/debug.h"
#include "gl/glsl_pieces.h"

namespace sb::techniques {

using core::Params;
using plugin::FrameInputs;

namespace {

const char* const kLookupMain = R"(
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 pos = texelFetch(position_tex, p, 0);
  if (pos.w == 0.0) { visibility = weight; return; }
  receiver_normal = texelFetch(normal_tex, p, 0).xyz;
  // An orthographic map's texels have one world size: its offset is in
  // world units. Its light is the sun, at infinity along the view's axis.
  receiver_world = light_orthographic
      ? pos.xyz + receiver_normal * normal_offset
      : offset_world(pos.xyz, receiver_normal, light_point, normal_offset);
  vec3 horizon_point = light_orthographic
      ? pos.xyz + vec3(light_view[0][2], light_view[1][2], light_view[2][2])
      : light_point;
  // Behind the light's eye plane the projection mirrors a point into the map
  // (w <= 0; a warped map's w may keep its sign there, hence the plane test
  // in the light's own view too). Every caster lies in front of that plane,
  // and the segment from such a point to the light's centre does not: it is
  // unshadowed.
  bool behind_light = (light_view_projection * vec4(receiver_world, 1.0)).w <= 0.0 ||
                      (light_view * vec4(receiver_world, 1.0)).z >= 0.0;
  vec3 t = light_coords(light_view_projection, receiver_world);
  // Outside the map's cone nothing stands between the point and the light's
  // centre: the cone holds every caster.
  if (behind_light || any(lessThan(t.xy, vec2(0.0))) || any(greaterThan(t.xy, vec2(1.0)))) {
    visibility = weight * above_horizon(receiver_normal, pos.xyz, horizon_point);
    return;
  }
  receiver_gradient = receiver_plane
      ? receiver_plane_gradient(light_view_projection, receiver_world, receiver_normal)
      : vec2(0.0);
  visibility = weight * above_horizon(receiver_normal, pos.xyz, horizon_point) * lit_fraction(t);
}
)";

}  // namespace

MapLookupPass::MapLookupPass(const std::string& name, const std::string& lit_fraction_glsl,
                             bool linear_compare, const std::string& kit_glsl)
    // The technique's GLSL is source string 1: a compile error names its
    // own lines ("1:12(3): error"), not the assembled shader's.
    : program_(name, {gl::kFullscreenVertexShader, "",
                      gl::assemble_glsl({{std::string("#version 450 core") + kMapLookupInputsGlsl +
                                          kLightLookupGlsl + kLightDepthGlsl + kit_glsl},
                                         {lit_fraction_glsl, 1, "lit_fraction"},
                                         {kLookupMain}})}),
      compare_sampler_(gl::make_sampler(linear_compare, /*compare=*/true, /*border=*/1.0f)),
      raw_sampler_(gl::make_sampler(/*linear=*/false, /*compare=*/false, /*border=*/1.0f)) {}

void MapLookupPass::draw(const FrameInputs& in, const LightFrustum& frustum,
                         const DepthMapSettings& settings, GLuint depth_map, float weight) const {
  glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
  glViewport(0, 0, in.width, in.height);
  glDisable(GL_DEPTH_TEST);
  program_.use();
  program_.set("light_view_projection", frustum.view_projection);
  program_.set("light_point", frustum.eye);
  program_.set("normal_offset", settings.normal_offset_per_distance(frustum));
  // Optimised out by variants that never read receiver_gradient.
  if (program_.has_uniform("receiver_plane"))
    program_.set("receiver_plane", settings.receiver_plane ? 1 : 0);
  program_.set("weight", weight);
  program_.set("light_view", frustum.view);
  if (program_.has_uniform("light_depth_range"))
    program_.set("light_depth_range", glm::vec2(frustum.near_plane, frustum.far_plane));
  program_.set("light_orthographic", frustum.orthographic ? 1 : 0);
  glBindTextureUnit(0, in.gbuffer_position);
  glBindTextureUnit(1, depth_map);
  glBindSampler(1, compare_sampler_.get());
  glBindTextureUnit(2, in.gbuffer_normal);
  glBindTextureUnit(3, depth_map);
  glBindSampler(3, raw_sampler_.get());
  gl::draw_fullscreen_triangle();
  glBindSampler(1, 0);
  glBindSampler(3, 0);
}

SingleMapTechnique::SingleMapTechnique(const Params& p, std::string name,
                                       std::string lit_fraction_glsl, bool linear_compare,
                                       std::string kit_glsl)
    : name_(std::move(name)),
      lit_fraction_glsl_(std::move(lit_fraction_glsl)),
      linear_compare_(linear_compare),
      kit_glsl_(std::move(kit_glsl)),
      settings_(depth_map_settings(p)) {}

void SingleMapTechnique::prepare(const FrameInputs& /*in*/) {
  map_ = DepthMap(settings_.size, settings_.depth_format);
  lookup_ = MapLookupPass(name_ + "_lookup", lit_fraction_glsl_, linear_compare_, kit_glsl_);
  set_uniforms(lookup_.program());
  gl::throw_if_errors(name_ + " prepare");
}

LightFrustum SingleMapTechnique::fit(const FrameInputs& in) const {
  return fit_single_map_frustum(*in.scene);
}

void SingleMapTechnique::render(const FrameInputs& in, gl::PassTimer& timer) {
  LightFrustum frustum;
  {
    auto pass = timer.scope("shadow_map");
    frustum = fit(in);
    map_.render(*in.gpu, frustum, settings_.cull, settings_.bias);
  }
  auto pass = timer.scope("lookup");
  set_light_uniforms(lookup_.program(), frustum, *in.scene);
  lookup_.draw(in, frustum, settings_, map_.texture());
}

}  // namespace sb::techniques
