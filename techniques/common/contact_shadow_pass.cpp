#include "common/contact_shadow_pass.h"

#include "common/glsl_rotation_noise.h"
#include "gl/debug.h"
#include "gl/objects.h"

namespace sb::techniques {

using core::Params;
using core::ParamSpec;
using plugin::FrameInputs;

namespace {

// The march of the header's rule; the noise (kRotationNoiseGlsl) goes before it.
const char* const kContactMain = R"(
in vec2 uv;
layout(binding = 0) uniform sampler2D position_tex;
layout(binding = 2) uniform sampler2D normal_tex;
uniform mat4 view;
uniform mat4 view_projection;
uniform vec3 eye;           // the camera's position
uniform vec3 light_point;   // a local light's centre
uniform vec3 to_sun;        // the sun's direction, unit
uniform bool sun;
uniform float march_length;
uniform int steps;
uniform float thickness;
uniform float pixel_world;  // a pixel's world size per unit of view depth
out float visibility;

float view_depth(vec3 world) { return -(view * vec4(world, 1.0)).z; }

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 pos = texelFetch(position_tex, p, 0);
  if (pos.w < 0.5) { visibility = 1.0; return; }
  vec3 n = texelFetch(normal_tex, p, 0).xyz;
  vec3 d = sun ? to_sun : light_point - pos.xyz;
  float reach = sun ? march_length : min(march_length, length(d));
  d = normalize(d);
  if (dot(n, d) <= 0.0) { visibility = 0.0; return; }
  ivec2 size = textureSize(position_tex, 0);
  vec3 start = pos.xyz + n * (0.25 * pixel_world * view_depth(pos.xyz));
  float step_length = reach / float(steps);
  float jitter = interleaved_gradient_noise(gl_FragCoord.xy);
  for (int i = 0; i < steps; ++i) {
    vec3 s = start + d * ((float(i) + jitter) * step_length);
    vec4 c = view_projection * vec4(s, 1.0);
    if (c.w <= 0.0) break;
    vec2 ndc = c.xy / c.w;
    if (any(greaterThan(abs(ndc), vec2(1.0)))) break;
    ivec2 q = min(ivec2((ndc * 0.5 + 0.5) * vec2(size)), size - 1);
    if (q == p) continue;
    vec4 seen = texelFetch(position_tex, q, 0);
    vec4 seen_normal = texelFetch(normal_tex, q, 0);
    if (seen.w < 0.5 || seen_normal.w < 0.5) continue;
    // The seen triangle's plane where the camera ray through s meets it
    // (E + t·(s − E)), not its depth at q's centre: a step a fraction of a
    // pixel beside a steep surface is not behind it.
    float z = view_depth(s);
    float facing = dot(seen_normal.xyz, s - eye);
    float behind = abs(facing) > 1e-4 * length(s - eye)
        ? (1.0 - dot(seen_normal.xyz, seen.xyz - eye) / facing) * z
        : z - view_depth(seen.xyz);
    if (behind > 0.0 && behind < thickness) { visibility = 0.0; return; }
  }
  visibility = 1.0;
}
)";

// "a positive number" unless the value is > 0.
ParamSpec positive(ParamSpec spec) {
  spec.rule = [](const nlohmann::json& v) -> std::string {
    return v.get<double>() > 0.0 ? "" : "a number > 0";
  };
  spec.rule_doc = "> 0";
  return spec;
}

}  // namespace

std::vector<ParamSpec> contact_shadow_params(const std::string& prefix) {
  return {positive(core::float_param(prefix + "length", 0.5, 0.0, 1e6,
                                     "contact shadows: march length from the surface towards the "
                                     "light, world units")),
          core::int_param(prefix + "steps", 16, 1, 256,
                          "contact shadows: steps along the march (samples of the depth buffer)"),
          positive(core::float_param(prefix + "thickness", 0.05, 0.0, 1e6,
                                     "contact shadows: how deep behind its visible surface an "
                                     "occluder is assumed, world units of view depth"))};
}

ContactShadowSettings contact_shadow_settings(const Params& p, const std::string& prefix) {
  return {.length = p.get_float(prefix + "length"),
          .steps = p.get_int(prefix + "steps"),
          .thickness = p.get_float(prefix + "thickness")};
}

ContactShadowPass::ContactShadowPass(const ContactShadowSettings& settings)
    : settings_(settings),
      program_("contact_shadows",
               {gl::kFullscreenVertexShader, "",
                std::string("#version 450 core\n") + kRotationNoiseGlsl + kContactMain}) {
  program_.set("march_length", settings_.length);
  program_.set("steps", settings_.steps);
  program_.set("thickness", settings_.thickness);
  gl::throw_if_errors("contact shadows prepare");
}

void ContactShadowPass::draw(const FrameInputs& in, ContactCombine combine) const {
  glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
  glViewport(0, 0, in.width, in.height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_SCISSOR_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  const core::AreaLight& light = in.scene->light;
  program_.use();
  program_.set("view", in.view);
  program_.set("view_projection", in.view_projection);
  program_.set("eye", glm::vec3(glm::inverse(in.view)[3]));
  program_.set("sun", light.is_sun() ? 1 : 0);
  program_.set("to_sun", light.to_sun());
  program_.set("light_point", light.center);
  // A perspective projection's pixel at view depth z is 2z / (P[1][1]·height) wide.
  program_.set("pixel_world", 2.0f / (in.projection[1][1] * float(in.height)));
  glBindTextureUnit(0, in.gbuffer_position);
  glBindTextureUnit(2, in.gbuffer_normal);
  if (combine == ContactCombine::Min) {
    glEnable(GL_BLEND);
    glBlendEquation(GL_MIN);  // factors are ignored by GL_MIN
  } else {
    glDisable(GL_BLEND);
  }
  gl::draw_fullscreen_triangle();
  glDisable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
}

}  // namespace sb::techniques
