#include "shadow_map/extended_light_map.h"

#include <array>
#include <string>

#include "gl/debug.h"

namespace sb::techniques::shadow_map {

using gl::DrawInfo;
using gl::GpuScene;

namespace {

// The channels as functions of the fragment's world point and normal.
const char* const kChannels = R"(#version 450 core
in vec3 v_world;
in vec3 v_normal;
uniform mat4 light_view;
uniform vec3 light_point;
uniform vec2 light_depth_range;  // near, far along the light's axis
out vec4 color;
float depth01() {
  float z = -(light_view * vec4(v_world, 1.0)).z;
  return clamp((z - light_depth_range.x) / (light_depth_range.y - light_depth_range.x), 0.0, 1.0);
}
float irradiance() {
  vec3 to_light = light_point - v_world;
  float r = length(to_light);
  // Both sides of a double-sided or open surface face the light they see.
  float cos_theta = abs(dot(normalize(v_normal), to_light / r));
  float ratio = light_depth_range.x / r;
  return clamp(cos_theta * ratio * ratio, 0.0, 1.0);
}
)";

// Alpha-tested meshes: the texel the depth pass and the ray tracer test
// (common/depth_pass.cpp). Opaque meshes get a mask() that keeps every
// fragment, so that their early depth test survives.
const char* const kMask = R"(
in vec2 v_uv;
layout(binding = 0) uniform sampler2D base_color;
uniform float alpha_cutoff;
void mask() { if (texture(base_color, v_uv).a < alpha_cutoff) discard; }
)";
const char* const kNoMask = R"(
void mask() {}
)";

ExtendedLightMap::Programs programs(const std::string& name, const char* body) {
  const std::string opaque = std::string(kChannels) + kNoMask + body;
  const std::string masked = std::string(kChannels) + kMask + body;
  return {gl::Program(name, {gl::kSceneVertexShader, "", opaque}),
          gl::Program(name + "_masked", {gl::kSceneVertexShader, "", masked})};
}

GLenum depth_format(ShadowChannel s) {
  return s == ShadowChannel::Depth32f ? GL_DEPTH_COMPONENT32F : GL_DEPTH_COMPONENT24;
}

}  // namespace

ExtendedLightMap::ExtendedLightMap(const ExtendedLightMapSettings& s) : settings_(s) {
  color_ = gl::make_texture_2d(GL_RGBA8, s.size, s.size);
  depth_ = gl::make_depth_texture(depth_format(s.shadow), s.size, s.size, /*compare=*/false);
  framebuffer_ = gl::make_framebuffer({color_.get()}, depth_.get());
  both_ = programs("elm_both", R"(
void main() { mask(); float e = irradiance(); color = vec4(e, e, e, depth01()); }
)");
  shadow_only_ = programs("elm_shadow_channel", R"(
void main() { mask(); color = vec4(0.0, 0.0, 0.0, depth01()); }
)");
  light_only_ = programs("elm_light_channel", R"(
void main() { mask(); float e = irradiance(); color = vec4(e, e, e, 0.0); }
)");
  // Opaque meshes need no fragment shader for depth alone.
  depth_only_ = {gl::Program("elm_depth", {gl::kSceneVertexShader, "", ""}),
                 gl::Program("elm_depth_masked",
                             {gl::kSceneVertexShader, "", std::string(kChannels) + kMask + R"(
void main() { mask(); }
)"})};
  gl::throw_if_errors("creating an extended light map");
}

void ExtendedLightMap::draw(const GpuScene& gpu, const LightFrustum& f, const Programs& programs,
                            bool writes_depth) {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
  glViewport(0, 0, settings_.size, settings_.size);
  glEnable(GL_DEPTH_TEST);
  // The light channel's own pass keeps the fragments the shadow channel
  // kept: the same polygon offset gives the same depths, and LEQUAL passes
  // exactly those.
  glDepthFunc(writes_depth ? GL_LESS : GL_LEQUAL);
  glDepthMask(writes_depth ? GL_TRUE : GL_FALSE);
  if (settings_.bias.constant != 0.0f || settings_.bias.slope != 0.0f) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(settings_.bias.slope, settings_.bias.constant);
  }
  for (const gl::Program* program : {&programs.opaque, &programs.masked}) {
    program->set_if_active("view_projection", f.view_projection);
    program->set_if_active("light_view", f.view);
    program->set_if_active("light_point", f.eye);
    program->set_if_active("light_depth_range", glm::vec2(f.near_plane, f.far_plane));
  }
  // Alpha-tested meshes go through their mask, as in every depth pass: a
  // leaf quad's transparent texels cast no shadow.
  const gl::Program* current = nullptr;
  gpu.draw_casters_and_map_receivers([&](const DrawInfo& d) {
    const gl::Program* wanted = d.alpha_tested ? &programs.masked : &programs.opaque;
    if (wanted != current) {
      wanted->use();
      current = wanted;
    }
    if (d.alpha_tested) {
      programs.masked.set("alpha_cutoff", d.alpha_cutoff);
      glBindTextureUnit(0, d.texture);
    }
    set_depth_pass_cull(settings_.cull, d);
  });
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_CULL_FACE);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void ExtendedLightMap::render_shadow_channel(const GpuScene& gpu, const LightFrustum& f) {
  glClearNamedFramebufferfv(framebuffer_.get(), GL_DEPTH, 0, std::array<float, 1>{1.0f}.data());
  // Where nothing is seen: no light, and the far end of the depth range.
  glClearNamedFramebufferfv(framebuffer_.get(), GL_COLOR, 0,
                            std::array<float, 4>{0.0f, 0.0f, 0.0f, 1.0f}.data());
  const bool alpha = settings_.shadow == ShadowChannel::Alpha8;
  const bool light_too = settings_.light == LightChannel::SamePass;
  if (light_too) {
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, alpha ? GL_TRUE : GL_FALSE);
    draw(gpu, f, both_, true);
  } else if (alpha) {
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
    draw(gpu, f, shadow_only_, true);
  } else {
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    draw(gpu, f, depth_only_, true);
  }
}

void ExtendedLightMap::render_light_channel(const GpuScene& gpu, const LightFrustum& f) {
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
  draw(gpu, f, light_only_, false);
}

const char* const kAlpha8LookupGlsl = R"(
layout(binding = 4) uniform sampler2D light_map;
// Both distances quantised to 8 bits, as the alpha test compared them: lit
// when the receiver is at most bias_steps steps behind the stored occluder.
float alpha8_lit(vec3 t, float bias_steps) {
  float stored = floor(texture(light_map, t.xy).a * 255.0 + 0.5);
  float receiver = floor(depth01(receiver_view_depth()) * 255.0 + 0.5);
  return receiver - stored <= bias_steps ? 1.0 : 0.0;
}
)";

}  // namespace sb::techniques::shadow_map
