#include "cascaded/cascade_depth_array.h"

#include <array>

#include "gl/debug.h"

namespace sb::techniques::cascaded {

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

// Alpha-tested casters only: a discard would cost opaque ones early depth tests.
const char* const kMaskedDepthFragment = R"(#version 450 core
in vec2 v_uv;
layout(binding = 0) uniform sampler2D base_color;
uniform float alpha_cutoff;
void main() {
  if (texture(base_color, v_uv).a < alpha_cutoff) discard;
}
)";

}  // namespace

CascadeDepthArray::CascadeDepthArray(int size, int layers, GLenum depth_format) : size_(size) {
  texture_ = gl::make_texture_2d_array(depth_format, size, size, layers);
  for (int layer = 0; layer < layers; ++layer) {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    glNamedFramebufferTextureLayer(id, GL_DEPTH_ATTACHMENT, texture_.get(), 0, layer);
    glNamedFramebufferDrawBuffer(id, GL_NONE);
    glNamedFramebufferReadBuffer(id, GL_NONE);
    framebuffers_.emplace_back(id);
  }
  program_ = gl::Program("cascade_depth", {kDepthVertex, "", ""});
  masked_program_ = gl::Program("cascade_depth_masked", {kDepthVertex, "", kMaskedDepthFragment});
  gl::throw_if_errors("creating the cascades' depth maps");
}

void CascadeDepthArray::render(const gl::GpuScene& gpu, int layer,
                               const glm::mat4& light_view_projection, CullMode cull,
                               DepthBias bias) const {
  const GLuint fb = framebuffers_[size_t(layer)].get();
  glBindFramebuffer(GL_FRAMEBUFFER, fb);
  glViewport(0, 0, size_, size_);
  glClearNamedFramebufferfv(fb, GL_DEPTH, 0, std::array<float, 1>{1.0f}.data());
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  if (bias.constant != 0.0f || bias.slope != 0.0f) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(bias.slope, bias.constant);
  }
  program_.set("light_view_projection", light_view_projection);
  masked_program_.set("light_view_projection", light_view_projection);
  const gl::Program* current = nullptr;
  gpu.draw_casters([&](const gl::DrawInfo& d) {
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
  });
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_CULL_FACE);
}

}  // namespace sb::techniques::cascaded
