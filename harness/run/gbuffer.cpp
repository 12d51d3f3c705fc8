#include "run/gbuffer.h"

#include <algorithm>

#include "gl/debug.h"

namespace sb::run {

using core::ImageF;
using core::Scene;
using gl::DrawInfo;
using gl::GpuScene;
using plugin::FrameInputs;

namespace {

// The geometric normal comes from the triangle itself, exactly as the ray
// tracer sees it, so the reference can offset its rays consistently.
const char* const kGBufferGeometry = R"(#version 450 core
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
in vec3 v_world[];
in vec3 v_normal[];
in vec2 v_uv[];
out vec3 g_world;
out vec3 g_normal;
out vec2 g_uv;
flat out vec3 g_face_normal;
void main() {
  vec3 n = normalize(cross(v_world[1] - v_world[0], v_world[2] - v_world[0]));
  for (int i = 0; i < 3; ++i) {
    g_world = v_world[i];
    g_normal = v_normal[i];
    g_uv = v_uv[i];
    g_face_normal = n;
    gl_Position = gl_in[i].gl_Position;
    EmitVertex();
  }
  EndPrimitive();
}
)";

const char* const kGBufferFragment = R"(#version 450 core
in vec3 g_world;
in vec3 g_normal;
in vec2 g_uv;
flat in vec3 g_face_normal;
layout(binding = 0) uniform sampler2D base_color;
uniform vec3 albedo;
uniform bool textured;
uniform bool alpha_test;
uniform float alpha_cutoff;
uniform bool casts_shadow;
layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_geometric_normal;
layout(location = 2) out vec4 out_shading_normal;
layout(location = 3) out vec4 out_albedo;
void main() {
  vec4 c = textured ? texture(base_color, g_uv) : vec4(1.0);
  if (alpha_test && c.a < alpha_cutoff) discard;  // the same texel the ray tracer tests
  // Seen from behind, a surface shows its back: flip both normals.
  float side = gl_FrontFacing ? 1.0 : -1.0;
  out_position = vec4(g_world, 1.0);
  // w: 1 on a caster, 0 on a mesh that casts no shadow (a receiver).
  out_geometric_normal = vec4(side * g_face_normal, casts_shadow ? 1.0 : 0.0);
  out_shading_normal = vec4(side * normalize(g_normal), 0.0);
  out_albedo = vec4(albedo * c.rgb, 1.0);
}
)";

const char* const kShadingFragment = R"(#version 450 core
in vec2 uv;
layout(binding = 0) uniform sampler2D position_tex;
layout(binding = 1) uniform sampler2D normal_tex;
layout(binding = 2) uniform sampler2D albedo_tex;
layout(binding = 3) uniform sampler2D visibility_tex;
// w = 1: a local light at xyz; w = 0: the sun, xyz towards it.
uniform vec4 light_position;
uniform float light_intensity;
uniform vec3 ambient;
uniform vec3 background;
out vec4 color;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 pos = texelFetch(position_tex, p, 0);
  if (pos.w == 0.0) { color = vec4(background, 1.0); return; }
  vec3 n = texelFetch(normal_tex, p, 0).xyz;
  vec3 albedo = texelFetch(albedo_tex, p, 0).rgb;
  float v = texelFetch(visibility_tex, p, 0).r;
  vec3 l = normalize(light_position.xyz - light_position.w * pos.xyz);
  vec3 radiance = albedo * (ambient + v * light_intensity * max(dot(n, l), 0.0));
  color = vec4(pow(clamp(radiance, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
)";

}  // namespace

FrameTargets::FrameTargets(int width, int height) : width_(width), height_(height) {
  position_ = gl::make_texture_2d(GL_RGBA32F, width, height);
  geometric_normal_ = gl::make_texture_2d(GL_RGBA32F, width, height);
  shading_normal_ = gl::make_texture_2d(GL_RGBA32F, width, height);
  albedo_ = gl::make_texture_2d(GL_RGBA8, width, height);
  depth_stencil_ = gl::make_texture_2d(GL_DEPTH24_STENCIL8, width, height);
  pristine_depth_stencil_ = gl::make_texture_2d(GL_DEPTH24_STENCIL8, width, height);
  visibility_ = gl::make_texture_2d(GL_R32F, width, height);
  shaded_ = gl::make_texture_2d(GL_RGBA32F, width, height);
  gbuffer_fb_ = gl::make_framebuffer(
      {position_.get(), geometric_normal_.get(), shading_normal_.get(), albedo_.get()},
      depth_stencil_.get(), GL_DEPTH_STENCIL_ATTACHMENT);
  visibility_fb_ =
      gl::make_framebuffer({visibility_.get()}, depth_stencil_.get(), GL_DEPTH_STENCIL_ATTACHMENT);
  shaded_fb_ = gl::make_framebuffer({shaded_.get()}, 0);
  gbuffer_program_ =
      gl::Program("gbuffer", {gl::kSceneVertexShader, kGBufferGeometry, kGBufferFragment});
  shading_program_ = gl::Program("shading", {gl::kFullscreenVertexShader, "", kShadingFragment});
  gl::throw_if_errors("creating frame targets");
}

void FrameTargets::render_gbuffer(const GpuScene& gpu, const glm::mat4& view_projection) {
  glBindFramebuffer(GL_FRAMEBUFFER, gbuffer_fb_.get());
  glViewport(0, 0, width_, height_);
  const float zero[4] = {0, 0, 0, 0};
  for (int i = 0; i < 4; ++i) glClearNamedFramebufferfv(gbuffer_fb_.get(), GL_COLOR, i, zero);
  glClearNamedFramebufferfi(gbuffer_fb_.get(), GL_DEPTH_STENCIL, 0, 1.0f, 0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);  // ground planes are single quads seen from either side
  gbuffer_program_.use();
  gbuffer_program_.set("view_projection", view_projection);
  const gl::Program& prog = gbuffer_program_;
  gpu.draw_all([&prog](const DrawInfo& d) {
    prog.set("albedo", d.albedo);
    prog.set("textured", d.texture != 0 ? 1 : 0);
    prog.set("alpha_test", d.alpha_tested ? 1 : 0);
    prog.set("alpha_cutoff", d.alpha_cutoff);
    prog.set("casts_shadow", d.casts_shadow ? 1 : 0);
    if (d.texture != 0) glBindTextureUnit(0, d.texture);
  });
  glCopyImageSubData(depth_stencil_.get(), GL_TEXTURE_2D, 0, 0, 0, 0, pristine_depth_stencil_.get(),
                     GL_TEXTURE_2D, 0, 0, 0, 0, width_, height_, 1);
  gl::throw_if_errors("G-buffer pass");
}

void FrameTargets::restore_gbuffer() {
  glCopyImageSubData(pristine_depth_stencil_.get(), GL_TEXTURE_2D, 0, 0, 0, 0, depth_stencil_.get(),
                     GL_TEXTURE_2D, 0, 0, 0, 0, width_, height_, 1);
  gl::throw_if_errors("restoring the G-buffer's depth-stencil");
}

void FrameTargets::render_shading(const Scene& scene) {
  glBindFramebuffer(GL_FRAMEBUFFER, shaded_fb_.get());
  glViewport(0, 0, width_, height_);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_BLEND);
  shading_program_.use();
  shading_program_.set("light_position", scene.light.is_sun()
                                             ? glm::vec4(scene.light.to_sun(), 0.0f)
                                             : glm::vec4(scene.light.center, 1.0f));
  shading_program_.set("light_intensity", scene.light.intensity);
  shading_program_.set("ambient", scene.ambient);
  shading_program_.set("background", glm::vec3(0.55f, 0.65f, 0.8f));
  glBindTextureUnit(0, position_.get());
  glBindTextureUnit(1, shading_normal_.get());
  glBindTextureUnit(2, albedo_.get());
  glBindTextureUnit(3, visibility_.get());
  gl::draw_fullscreen_triangle();
  gl::throw_if_errors("shading pass");
}

FrameInputs FrameTargets::inputs(const Scene& scene, const GpuScene& gpu, const glm::mat4& view,
                                 const glm::mat4& projection) const {
  FrameInputs in;
  in.width = width_;
  in.height = height_;
  in.scene = &scene;
  in.gpu = &gpu;
  in.view = view;
  in.projection = projection;
  in.view_projection = projection * view;
  in.gbuffer_position = position_.get();
  in.gbuffer_normal = geometric_normal_.get();
  in.gbuffer_shading_normal = shading_normal_.get();
  in.gbuffer_albedo = albedo_.get();
  in.depth_stencil = depth_stencil_.get();
  in.visibility_framebuffer = visibility_fb_.get();
  in.visibility_texture = visibility_.get();
  return in;
}

ImageF read_texture(GLuint texture, int width, int height, int channels) {
  const GLenum format = channels == 1   ? GL_RED
                        : channels == 2 ? GL_RG
                        : channels == 3 ? GL_RGB
                                        : GL_RGBA;
  ImageF raw(width, height, channels);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(texture, 0, format, GL_FLOAT, GLsizei(raw.data.size() * sizeof(float)),
                    raw.data.data());
  gl::throw_if_errors("reading back a texture");
  ImageF out(width, height, channels);
  const size_t row = size_t(width) * channels;
  for (int y = 0; y < height; ++y)
    std::copy_n(raw.data.begin() + std::ptrdiff_t(size_t(height - 1 - y) * row), row,
                out.data.begin() + std::ptrdiff_t(size_t(y) * row));
  return out;
}

ImageF FrameTargets::read_positions() const {
  return read_texture(position_.get(), width_, height_, 4);
}
ImageF FrameTargets::read_geometric_normals() const {
  return read_texture(geometric_normal_.get(), width_, height_, 3);
}
ImageF FrameTargets::read_receiver_mask() const {
  const ImageF normals = read_texture(geometric_normal_.get(), width_, height_, 4);
  const ImageF positions = read_positions();
  ImageF mask(width_, height_, 1);
  for (size_t i = 0; i < mask.data.size(); ++i)
    mask.data[i] =
        positions.data[4 * i + 3] != 0.0f && normals.data[4 * i + 3] == 0.0f ? 1.0f : 0.0f;
  return mask;
}
ImageF FrameTargets::read_visibility() const {
  return read_texture(visibility_.get(), width_, height_, 1);
}
ImageF FrameTargets::read_shaded() const {
  // RGBA as stored, then RGB here, not the driver's format conversion (what
  // that saves was within the noise of two runs: docs/performance.md).
  const ImageF rgba = read_texture(shaded_.get(), width_, height_, 4);
  ImageF rgb(width_, height_, 3);
  for (size_t i = 0; i < rgb.pixel_count(); ++i)
    std::copy_n(rgba.data.begin() + std::ptrdiff_t(i * 4), 3,
                rgb.data.begin() + std::ptrdiff_t(i * 3));
  return rgb;
}

void FrameTargets::upload_visibility(const ImageF& v) {
  std::vector<float> flipped(v.data.size());
  for (int y = 0; y < height_; ++y)
    std::copy_n(v.data.begin() + std::ptrdiff_t(size_t(y) * width_), width_,
                flipped.begin() + std::ptrdiff_t(size_t(height_ - 1 - y) * width_));
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(visibility_.get(), 0, 0, 0, width_, height_, GL_RED, GL_FLOAT,
                      flipped.data());
  gl::throw_if_errors("uploading visibility");
}

}  // namespace sb::run
