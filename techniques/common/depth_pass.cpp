#include "common/depth_pass.h"

#include <array>
#include <stdexcept>

#include "core/error.h"
#include "gl/debug.h"

namespace sb::shadow {
namespace {

const char* const kDepthVertex = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 2) in vec2 uv;
uniform mat4 light_view_projection;
out vec2 v_uv;
void main() {
  v_uv = uv;
  gl_Position = light_view_projection * vec4(position, 1.0);
}
)";

// Alpha-tested casters only: a fragment shader (and its discard) would cost
// every opaque caster its early depth test.
const char* const kMaskedDepthFragment = R"(#version 450 core
in vec2 v_uv;
layout(binding = 0) uniform sampler2D base_color;
uniform float alpha_cutoff;
void main() {
  if (texture(base_color, v_uv).a < alpha_cutoff) discard;
}
)";

void set_cull(CullMode cull, bool double_sided) {
  if (cull == CullMode::None || double_sided) {
    glDisable(GL_CULL_FACE);
  } else {
    glEnable(GL_CULL_FACE);
    glCullFace(cull == CullMode::Back ? GL_BACK : GL_FRONT);
  }
}

}  // namespace

CullMode cull_mode_from_string(const std::string& s) {
  if (s == "none") return CullMode::None;
  if (s == "back") return CullMode::Back;
  if (s == "front") return CullMode::Front;
  throw std::logic_error("unknown cull mode '" + s + "'");
}

std::vector<ParamSpec> depth_map_params(int default_size) {
  return {int_param("size", default_size, 16, 16384, "shadow-map side in texels"),
          float_param("constant_bias", 4.0, -1e6, 1e6, "glPolygonOffset units (depth pass)"),
          float_param("slope_bias", 2.0, -1e3, 1e3, "glPolygonOffset factor (depth pass)"),
          choice_param("cull", "front", {"none", "back", "front"},
                       "faces culled when rendering the map (front: render back faces, no acne on "
                       "lit closed surfaces)"),
          float_param("normal_offset", 0.0, 0.0, 64.0,
                      "receiver offset along its normal, in shadow-map texels")};
}

DepthMapSettings depth_map_settings(const Params& p) {
  DepthMapSettings s;
  s.size = p.get_int("size");
  s.bias = {p.get_float("constant_bias"), p.get_float("slope_bias")};
  s.cull = cull_mode_from_string(p.get_string("cull"));
  s.normal_offset = p.get_float("normal_offset");
  return s;
}

DepthMap::DepthMap(int size, bool compare, bool linear) : size_(size) {
  texture_ = gl::make_depth_texture(GL_DEPTH_COMPONENT32F, size, size, compare);
  if (linear) {
    glTextureParameteri(texture_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  }
  framebuffer_ = gl::make_framebuffer({}, texture_.get());
  program_ = gl::Program("shadow_depth", {kDepthVertex, "", ""});
  masked_program_ = gl::Program("shadow_depth_masked", {kDepthVertex, "", kMaskedDepthFragment});
  gl::throw_if_errors("creating a shadow map");
}

void DepthMap::render(const GpuScene& gpu, const LightFrustum& f, CullMode cull, DepthBias bias) {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
  glViewport(0, 0, size_, size_);
  glClearNamedFramebufferfv(framebuffer_.get(), GL_DEPTH, 0, std::array<float, 1>{1.0f}.data());
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  if (bias.constant != 0.0f || bias.slope != 0.0f) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(bias.slope, bias.constant);
  }
  program_.set("light_view_projection", f.view_projection);
  masked_program_.set("light_view_projection", f.view_projection);
  const gl::Program* current = nullptr;
  gpu.draw_casters([&](const DrawInfo& d) {
    const gl::Program* wanted = d.alpha_tested ? &masked_program_ : &program_;
    if (wanted != current) {
      wanted->use();
      current = wanted;
    }
    if (d.alpha_tested) {
      masked_program_.set("alpha_cutoff", d.alpha_cutoff);
      glBindTextureUnit(0, d.texture);
    }
    set_cull(cull, d.double_sided);
  });
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_CULL_FACE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

const char* const kLightLookupGlsl = R"(
vec3 light_coords(mat4 light_view_projection, vec3 world) {
  vec4 c = light_view_projection * vec4(world, 1.0);
  vec3 ndc = c.xyz / c.w;
  vec3 t = ndc * 0.5 + 0.5;
  t.z = min(t.z, 1.0);
  return t;
}
vec3 offset_world(vec3 world, vec3 geometric_normal, vec3 light_point, float normal_offset) {
  return world + geometric_normal * (normal_offset * distance(world, light_point));
}
// 1 when the light point lies above the surface's tangent plane; below it the
// surface itself occludes the light (the reference counts it so too).
float above_horizon(vec3 geometric_normal, vec3 world, vec3 light_point) {
  return dot(geometric_normal, light_point - world) > 0.0 ? 1.0 : 0.0;
}
)";

}  // namespace sb::shadow
