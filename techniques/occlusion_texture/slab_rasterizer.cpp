#include "occlusion_texture/slab_rasterizer.h"

#include <array>
#include <string>

#include "core/error.h"
#include "gl/debug.h"

namespace sb::techniques::occlusion_texture {

using core::JobError;
using gl::DrawInfo;
using gl::GpuScene;

const char* const kSlicingUniformsGlsl = R"(
uniform vec3 light_center;
uniform vec3 light_u;
uniform vec3 light_v;
uniform vec3 light_n;
uniform vec2 light_half;
uniform float z0;
uniform float thickness;
uniform vec2 origin;
uniform vec2 scale;
uniform float proj_a;
uniform float proj_b;
vec3 to_light(vec3 world) {
  vec3 d = world - light_center;
  return vec3(dot(d, light_u), dot(d, light_v), dot(d, light_n));
}
)";

namespace {

const char* const kSlabVertex = R"(
layout(location = 0) in vec3 position;
layout(location = 2) in vec2 uv;
out float v_depth;
out vec2 v_uv;
void main() {
  vec3 l = to_light(position);
  v_depth = l.z;
  v_uv = uv;
  // NDC = 2q − 1 = 2 (xy − origin) ∘ scale / (a z + b): the divide by w.
  gl_Position = vec4(2.0 * (l.xy - origin) * scale, 0.0, proj_a * l.z + proj_b);
}
)";

const char* const kSlabFragment = R"(
in float v_depth;
in vec2 v_uv;
layout(binding = 0) uniform sampler2D base_color;
uniform bool masked;
uniform float alpha_cutoff;
uniform bool thin_occluder_fix;
void mark(int slab, inout vec4 outs[TEXTURES]) {
  for (int t = 0; t < TEXTURES; ++t)
    for (int c = 0; c < 4; ++c)
      if (t * 4 + c == slab) outs[t][c] = 1.0;
}
void main() {
  if (masked && texture(base_color, v_uv).a < alpha_cutoff) discard;
  int slab = clamp(int(floor((v_depth - z0) / thickness)), 0, SLABS - 1);
  vec4 outs[TEXTURES];
  for (int t = 0; t < TEXTURES; ++t) outs[t] = vec4(0.0);
  mark(slab, outs);
  // The paper's fix: the texture projected onto its successor, away from the light.
  if (thin_occluder_fix && slab + 1 < SLABS) mark(slab + 1, outs);
  WRITE_OUTPUTS
}
)";

std::string slab_fragment(int slabs, int textures) {
  std::string outputs, writes;
  for (int t = 0; t < textures; ++t) {
    outputs += "layout(location = " + std::to_string(t) + ") out vec4 slab_group" +
               std::to_string(t) + ";\n";
    writes += "slab_group" + std::to_string(t) + " = outs[" + std::to_string(t) + "];\n  ";
  }
  std::string body = kSlabFragment;
  body.replace(body.find("WRITE_OUTPUTS"), 13, writes);
  return "#version 450 core\n#define SLABS " + std::to_string(slabs) + "\n#define TEXTURES " +
         std::to_string(textures) + "\n" + kSlicingUniformsGlsl + outputs + body;
}

}  // namespace

void set_slicing_uniforms(const gl::Program& program, const Slicing& s) {
  program.set("light_center", s.light.center);
  program.set("light_u", s.light.u);
  program.set("light_v", s.light.v);
  program.set("light_n", s.light.n);
  program.set("z0", s.z0);
  program.set("thickness", s.thickness);
  program.set("origin", s.origin);
  program.set("scale", s.scale);
  program.set("proj_a", s.a);
  program.set("proj_b", s.b);
}

SlabRasterizer::SlabRasterizer(int slabs, int size, const std::vector<GLuint>& targets,
                               bool light_facing_only, bool thin_occluder_fix)
    : size_(size),
      textures_(int(targets.size())),
      light_facing_only_(light_facing_only),
      thin_occluder_fix_(thin_occluder_fix) {
  GLuint fb = 0;
  glCreateFramebuffers(1, &fb);
  framebuffer_ = gl::Framebuffer(fb);
  std::vector<GLenum> buffers;
  for (int t = 0; t < textures_; ++t) {
    glNamedFramebufferTexture(fb, GLenum(GL_COLOR_ATTACHMENT0 + t), targets[size_t(t)], 0);
    buffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + t));
  }
  glNamedFramebufferDrawBuffers(fb, GLsizei(buffers.size()), buffers.data());
  if (glCheckNamedFramebufferStatus(fb, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw JobError("occlusion textures: the slab framebuffer is incomplete");
  program_ = gl::Program("occlusion_slabs",
                         {std::string("#version 450 core\n") + kSlicingUniformsGlsl + kSlabVertex,
                          "", slab_fragment(slabs, textures_)});
  program_.set("thin_occluder_fix", thin_occluder_fix_ ? 1 : 0);
  gl::throw_if_errors("occlusion textures: slab pass");
}

void SlabRasterizer::render(const GpuScene& gpu, const Slicing& slicing) const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
  glViewport(0, 0, size_, size_);
  for (int t = 0; t < textures_; ++t)
    glClearNamedFramebufferfv(framebuffer_.get(), GL_COLOR, t,
                              std::array<float, 4>{0.0f, 0.0f, 0.0f, 0.0f}.data());
  if (slicing.no_casters) return;
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendEquation(GL_MAX);
  glBlendFunc(GL_ONE, GL_ONE);
  program_.use();
  set_slicing_uniforms(program_, slicing);
  gpu.draw_casters([&](const DrawInfo& d) {
    program_.set("masked", d.alpha_tested ? 1 : 0);
    // Seen from the light (looking along +n, x = u and y = v up), a face
    // that looks at the light winds clockwise: GL's back face. Culling the
    // front ones keeps the light-facing side.
    if (light_facing_only_ && d.cullable && !d.double_sided) {
      glEnable(GL_CULL_FACE);
      glCullFace(GL_FRONT);
    } else {
      glDisable(GL_CULL_FACE);
    }
    if (d.alpha_tested) {
      program_.set("alpha_cutoff", d.alpha_cutoff);
      glBindTextureUnit(0, d.texture);
    }
  });
  glDisable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glDisable(GL_CULL_FACE);
  glCullFace(GL_BACK);
}

}  // namespace sb::techniques::occlusion_texture
