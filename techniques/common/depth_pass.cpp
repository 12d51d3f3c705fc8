#include "common/depth_pass.h"

#include <array>
#include <stdexcept>

#include "core/error.h"
#include "gl/debug.h"

namespace sb::techniques {

using core::as_map_size;
using core::bool_param;
using core::choice_param;
using core::float_param;
using core::int_param;
using core::Params;
using core::ParamSpec;
using gl::DrawInfo;
using gl::GpuScene;

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

}  // namespace

void set_depth_pass_cull(CullMode cull, const DrawInfo& d) {
  // Receivers, double-sided and open meshes keep every face.
  if (cull == CullMode::None || !d.casts_shadow || d.double_sided || !d.cullable) {
    glDisable(GL_CULL_FACE);
  } else {
    glEnable(GL_CULL_FACE);
    glCullFace(cull == CullMode::Back ? GL_BACK : GL_FRONT);
  }
}

CullMode cull_mode_from_string(const std::string& s) {
  if (s == "none") return CullMode::None;
  if (s == "back") return CullMode::Back;
  if (s == "front") return CullMode::Front;
  throw std::logic_error("unknown cull mode '" + s + "'");
}

std::vector<ParamSpec> depth_map_params(int default_size, const std::string& default_cull) {
  return {as_map_size(int_param("size", default_size, 16, 16384, "shadow-map side in texels")),
          choice_param("depth_format", "32f", {"32f", "24", "16"},
                       "depth-map format: 32-bit float, 24- or 16-bit normalised"),
          float_param("constant_bias", 4.0, -1e6, 1e6, "glPolygonOffset units (depth pass)"),
          float_param("slope_bias", 2.0, -1e3, 1e3, "glPolygonOffset factor (depth pass)"),
          choice_param("cull", default_cull, {"none", "back", "front"},
                       "faces culled when rendering the map (front: render back faces, no acne on "
                       "lit closed surfaces)"),
          float_param("normal_offset", 0.0, 0.0, 64.0,
                      "receiver offset along its normal, in shadow-map texels")};
}

ParamSpec receiver_plane_param() {
  return bool_param("receiver_plane_bias", false,
                    "compare each tap against the receiver's plane extended to the tap "
                    "(Isidoro 2006)");
}

DepthMapSettings depth_map_settings(const Params& p) {
  DepthMapSettings s;
  s.size = p.get_int("size");
  const std::string format = p.get_string("depth_format");
  s.depth_format = format == "16"   ? GL_DEPTH_COMPONENT16
                   : format == "24" ? GL_DEPTH_COMPONENT24
                                    : GL_DEPTH_COMPONENT32F;
  if (p.json().contains("receiver_plane_bias"))
    s.receiver_plane = p.get_bool("receiver_plane_bias");
  s.bias = {p.get_float("constant_bias"), p.get_float("slope_bias")};
  s.cull = cull_mode_from_string(p.get_string("cull"));
  // Warped maps have no single texel size to offset by: they leave it out.
  if (p.json().contains("normal_offset")) s.normal_offset = p.get_float("normal_offset");
  return s;
}

DepthMap::DepthMap(int size, GLenum depth_format) : size_(size) {
  texture_ = gl::make_depth_texture(depth_format, size, size, /*compare=*/false);
  framebuffer_ = gl::make_framebuffer({}, texture_.get());
  program_ = gl::Program("shadow_depth", {kDepthVertex, "", ""});
  masked_program_ = gl::Program("shadow_depth_masked", {kDepthVertex, "", kMaskedDepthFragment});
  gl::throw_if_errors("creating a shadow map");
}

void DepthMap::render(const GpuScene& gpu, const LightFrustum& f, CullMode cull, DepthBias bias,
                      bool receivers_too) {
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
  const auto setup = [&](const DrawInfo& d) {
    const gl::Program* wanted = d.alpha_tested ? &masked_program_ : &program_;
    if (wanted != current) {
      wanted->use();
      current = wanted;
    }
    if (d.alpha_tested) {
      masked_program_.set("alpha_cutoff", d.alpha_cutoff);
      glBindTextureUnit(0, d.texture);
    }
    set_depth_pass_cull(cull, d);
  };
  if (receivers_too)
    gpu.draw_casters_and_map_receivers(setup);
  else
    gpu.draw_casters(setup);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_CULL_FACE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

}  // namespace sb::techniques
