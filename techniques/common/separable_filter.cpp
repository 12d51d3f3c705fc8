#include "common/separable_filter.h"

#include <string>

#include "core/error.h"
#include "gl/debug.h"

namespace sb::techniques {

using core::JobError;

namespace {

const char* const kFilterFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2DArray source;
uniform int layer;
uniform ivec2 direction;
uniform int radius;
uniform float weights[63];
uniform bool log_sum_exp;
uniform float exponent;
out vec4 result;

vec4 tap(ivec2 p, int i, ivec2 last) {
  return texelFetch(source, ivec3(clamp(p + i * direction, ivec2(0), last), layer), 0);
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 last = textureSize(source, 0).xy - 1;
  if (!log_sum_exp) {
    vec4 sum = vec4(0.0);
    for (int i = -radius; i <= radius; ++i) sum += weights[i + radius] * tap(p, i, last);
    result = sum;
    return;
  }
  float m = tap(p, -radius, last).r;
  for (int i = -radius + 1; i <= radius; ++i) m = max(m, tap(p, i, last).r);
  float sum = 0.0;
  for (int i = -radius; i <= radius; ++i)
    sum += weights[i + radius] * exp(exponent * (tap(p, i, last).r - m));
  result = vec4(m + log(sum) / exponent);
}
)";

}  // namespace

gl::Texture make_array_texture(GLenum internal_format, int size, int layers) {
  return gl::make_texture_2d_array(internal_format, size, size, layers);
}

std::vector<gl::Framebuffer> layer_framebuffers(GLuint array_texture, int layers) {
  std::vector<gl::Framebuffer> out;
  for (int l = 0; l < layers; ++l) {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    out.emplace_back(id);
    glNamedFramebufferTextureLayer(id, GL_COLOR_ATTACHMENT0, array_texture, 0, l);
    glNamedFramebufferDrawBuffer(id, GL_COLOR_ATTACHMENT0);
    const GLenum status = glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
      throw JobError("array layer framebuffer incomplete (status 0x" + std::to_string(status) +
                     ")");
  }
  return out;
}

SeparableFilter::SeparableFilter(GLuint target, GLenum internal_format, int size, int layers,
                                 std::vector<float> weights, Mode mode, float exponent)
    : size_(size),
      layers_(layers),
      weights_(std::move(weights)),
      target_(target),
      scratch_(make_array_texture(internal_format, size, layers)),
      target_layers_(layer_framebuffers(target, layers)),
      scratch_layers_(layer_framebuffers(scratch_.get(), layers)),
      program_("separable_filter", {gl::kFullscreenVertexShader, "", kFilterFragment}) {
  program_.set("radius", taps() / 2);
  program_.set("weights", weights_);
  program_.set("log_sum_exp", mode == Mode::LogSumExp ? 1 : 0);
  if (mode == Mode::LogSumExp) program_.set("exponent", exponent);
  gl::throw_if_errors("creating a separable filter");
}

void SeparableFilter::apply() const {
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glViewport(0, 0, size_, size_);
  program_.use();
  // Horizontal: target -> scratch; vertical: scratch -> target.
  const struct {
    GLuint source;
    const std::vector<gl::Framebuffer>* destination;
    glm::ivec2 direction;
  } passes[2] = {{target_, &scratch_layers_, {1, 0}}, {scratch_.get(), &target_layers_, {0, 1}}};
  for (const auto& pass : passes) {
    program_.set("direction", pass.direction);
    glBindTextureUnit(0, pass.source);
    for (int l = 0; l < layers_; ++l) {
      program_.set("layer", l);
      glBindFramebuffer(GL_FRAMEBUFFER, (*pass.destination)[size_t(l)].get());
      gl::draw_fullscreen_triangle();
    }
  }
}

}  // namespace sb::techniques
