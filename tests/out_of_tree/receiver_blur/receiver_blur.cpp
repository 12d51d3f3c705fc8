// receiver_blur — hard shadows projected onto the planar receiver from
// the light's centre (Blinn's matrix), then blurred by a fixed world-space
// width read from a mip chain that a compute pass builds every frame.
//
// A demonstration of the plugin contract more than a technique to rank: it
// shades the planar receiver only (every other point counts as lit), and its
// blur ignores the distance to the casters. Per frame, timed:
//   occlusion — the casters, projected onto the receiver, into a square
//               texture laid over it (this family's need "receiver_basis");
//   mip_chain — a compute shader averages each level into the next;
//   lookup    — each G-buffer point on the plane reads a tent of taps
//               from the level whose texels are half as wide as `blur`.
// prepare() compiles and allocates only: the projection depends on the
// light, so it is redone in every frame.
#include <algorithm>
#include <cmath>
#include <memory>

#include "gl/gpu_scene.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "plugin/registry.h"
#include "receiver_basis.h"

namespace blurred {
namespace {

constexpr const char* kOcclusionVertex = R"(#version 450 core
layout(location = 0) in vec3 position;
uniform vec4 plane;        // n·x + d = 0
uniform vec3 light;        // the light's centre
uniform vec3 origin, axis_u, axis_v;
uniform vec2 half_extent;
void main() {
  // Blinn: the point where the ray from the light through `position` meets
  // the plane, homogeneous (w = n·(L − P)), so points at the light's height
  // go to infinity instead of dividing by zero.
  float l = dot(plane.xyz, light) + plane.w;
  float p = dot(plane.xyz, position) + plane.w;
  vec4 q = vec4(l * position - p * light, l - p);
  vec3 rel = q.xyz - origin * q.w;
  gl_Position = vec4(dot(rel, axis_u) / half_extent.x, dot(rel, axis_v) / half_extent.y, 0.0, q.w);
}
)";

constexpr const char* kOcclusionFragment = R"(#version 450 core
layout(location = 0) out float occlusion;
void main() { occlusion = 1.0; }
)";

constexpr const char* kMipCompute = R"(#version 450 core
layout(local_size_x = 8, local_size_y = 8) in;
layout(r32f, binding = 0) readonly uniform image2D finer;
layout(r32f, binding = 1) writeonly uniform image2D coarser;
void main() {
  ivec2 c = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(c, imageSize(coarser)))) return;
  ivec2 f = 2 * c;
  float sum = imageLoad(finer, f).r + imageLoad(finer, f + ivec2(1, 0)).r +
              imageLoad(finer, f + ivec2(0, 1)).r + imageLoad(finer, f + ivec2(1, 1)).r;
  imageStore(coarser, c, vec4(0.25 * sum));
}
)";

constexpr const char* kFullscreenVertex = R"(#version 450 core
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
)";

constexpr const char* kLookupFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D gbuffer_position;
layout(binding = 1) uniform sampler2D occlusion;
uniform vec4 plane;
uniform vec3 origin, axis_u, axis_v;
uniform vec2 half_extent;
uniform float on_plane_eps;  // world units
uniform float lod;
layout(location = 0) out float visibility;
void main() {
  vec4 p = texelFetch(gbuffer_position, ivec2(gl_FragCoord.xy), 0);
  visibility = 1.0;
  if (p.w == 0.0 || abs(dot(plane.xyz, p.xyz) + plane.w) > on_plane_eps) return;
  vec3 rel = p.xyz - origin;
  vec2 uv = 0.5 + 0.5 * vec2(dot(rel, axis_u) / half_extent.x, dot(rel, axis_v) / half_extent.y);
  // A 3×3 tent of bilinear taps one texel of that level apart: a single
  // tap would show the level's texel grid as blocks.
  float step = exp2(lod) / float(textureSize(occlusion, 0).x);
  float sum = 0.0;
  for (int j = -1; j <= 1; ++j)
    for (int i = -1; i <= 1; ++i)
      sum += float((2 - abs(i)) * (2 - abs(j))) * textureLod(occlusion, uv + step * vec2(i, j), lod).r;
  visibility = 1.0 - clamp(sum / 16.0, 0.0, 1.0);
}
)";

class BlurredVisibility final : public sb::Technique {
 public:
  explicit BlurredVisibility(const sb::Params& p)
      : size_(p.get_int("size")), blur_(p.get_float("blur")) {}

  void prepare(const sb::FrameInputs& in) override {
    occlusion_program_ =
        sb::gl::Program("receiver_blur occlusion", {kOcclusionVertex, "", kOcclusionFragment});
    mip_program_ = sb::gl::Program::compute("receiver_blur mip chain", kMipCompute);
    lookup_program_ =
        sb::gl::Program("receiver_blur lookup", {kFullscreenVertex, "", kLookupFragment});
    levels_ = 1 + int(std::floor(std::log2(double(size_))));
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    occlusion_ = sb::gl::Texture(tex);
    glTextureStorage2D(tex, levels_, GL_R32F, size_, size_);
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    occlusion_fbo_ = sb::gl::make_framebuffer({tex}, 0);
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    empty_vao_ = sb::gl::VertexArray(vao);
    // The basis is this family's need: read once, it never changes.
    basis_ = in.derived->get<ReceiverBasis>(kReceiverBasis);
  }

  void render(const sb::FrameInputs& in, sb::gl::PassTimer& timer) override {
    const auto& b = basis_;
    const glm::vec3 light = in.scene->light.center;
    {
      auto pass = timer.scope("occlusion");
      glBindFramebuffer(GL_FRAMEBUFFER, occlusion_fbo_.get());
      glViewport(0, 0, size_, size_);
      const float zero = 0.0f;
      glClearNamedFramebufferfv(occlusion_fbo_.get(), GL_COLOR, 0, &zero);
      occlusion_program_.use();
      occlusion_program_.set("plane", in.receiver_plane);
      occlusion_program_.set("light", light);
      occlusion_program_.set("origin", b.origin);
      occlusion_program_.set("axis_u", b.u);
      occlusion_program_.set("axis_v", b.v);
      occlusion_program_.set("half_extent", b.half_extent);
      in.gpu->draw_casters();
    }
    {
      auto pass = timer.scope("mip_chain");
      mip_program_.use();
      for (int level = 1; level < levels_; ++level) {
        glBindImageTexture(0, occlusion_.get(), level - 1, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
        glBindImageTexture(1, occlusion_.get(), level, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
        const int n = std::max(1, size_ >> level);
        glDispatchCompute(GLuint((n + 7) / 8), GLuint((n + 7) / 8), 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
      }
    }
    {
      auto pass = timer.scope("lookup");
      glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
      glViewport(0, 0, in.width, in.height);
      lookup_program_.use();
      lookup_program_.set("plane", in.receiver_plane);
      lookup_program_.set("origin", b.origin);
      lookup_program_.set("axis_u", b.u);
      lookup_program_.set("axis_v", b.v);
      lookup_program_.set("half_extent", b.half_extent);
      const float extent = 2.0f * std::max(b.half_extent.x, b.half_extent.y);
      lookup_program_.set("on_plane_eps", 1e-4f * extent);
      // The level whose texels are half the blur wide (level 0: extent /
      // size): the tent's taps then span the whole width.
      const float texel = 2.0f * std::min(b.half_extent.x, b.half_extent.y) / float(size_);
      lookup_program_.set("lod",
                          std::clamp(std::log2(0.5f * blur_ / texel), 0.0f, float(levels_ - 1)));
      glBindTextureUnit(0, in.gbuffer_position);
      glBindTextureUnit(1, occlusion_.get());
      glBindVertexArray(empty_vao_.get());
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }

 private:
  int size_;
  float blur_;
  int levels_ = 1;
  ReceiverBasis basis_;
  sb::gl::Program occlusion_program_, mip_program_, lookup_program_;
  sb::gl::Texture occlusion_;
  sb::gl::Framebuffer occlusion_fbo_;
  sb::gl::VertexArray empty_vao_;
};

}  // namespace
}  // namespace blurred

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  registry.add_provider(blurred::receiver_basis_provider());
  registry.add(
      {.name = "receiver_blur",
       .family = "receiver_blur",
       .summary = "hard shadow projected onto the planar receiver, blurred through a compute-built "
                  "mip chain (plugin demo; the receiver only)",
       .needs =
           sb::Needs{sb::need::kPlanarReceiver, sb::need::kOpaqueCasters, blurred::kReceiverBasis},
       .params = {sb::int_param("size", 512, 16, 4096, "occlusion texture size (texels a side)"),
                  sb::float_param("blur", 0.2, 0.0, 100.0,
                                  "blur width on the receiver, world units")},
       .create = [](const sb::Params& p) {
         return std::make_unique<blurred::BlurredVisibility>(p);
       }});
}
