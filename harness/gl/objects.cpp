#include "gl/objects.h"

#include <string>

#include "core/error.h"
#include "gl/allocation_meter.h"
#include "gl/storage_bytes.h"

namespace sb::gl {

using core::JobError;

void delete_texture(GLuint id) {
  meter_release(StorageKind::TextureName, id);
  glDeleteTextures(1, &id);
}

void delete_buffer(GLuint id) {
  meter_release(StorageKind::BufferName, id);
  glDeleteBuffers(1, &id);
}

void delete_renderbuffer(GLuint id) {
  meter_release(StorageKind::RenderbufferName, id);
  glDeleteRenderbuffers(1, &id);
}

namespace {

// Immutable storage of `target` (2D, 2D array or 3D), nearest filtering,
// clamped edges, metered.
Texture make_texture(GLenum target, GLenum internal_format, const TextureExtent& e) {
  // Sized first: an unknown format throws before any GL object exists.
  const std::int64_t bytes = texture_storage_bytes(internal_format, e);
  GLuint id = 0;
  glCreateTextures(target, 1, &id);
  if (target == GL_TEXTURE_2D)
    glTextureStorage2D(id, e.levels, internal_format, e.width, e.height);
  else
    glTextureStorage3D(id, e.levels, internal_format, e.width, e.height, e.depth);
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  if (target == GL_TEXTURE_3D) glTextureParameteri(id, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  meter_storage(StorageKind::TextureName, id, bytes);
  return Texture(id);
}

}  // namespace

Texture make_texture_2d(GLenum internal_format, int width, int height) {
  return make_mipmapped_texture_2d(internal_format, width, height, 1);
}

Texture make_mipmapped_texture_2d(GLenum internal_format, int width, int height, int levels) {
  return make_texture(GL_TEXTURE_2D, internal_format,
                      {.width = width, .height = height, .levels = levels});
}

Texture make_texture_2d_array(GLenum internal_format, int width, int height, int layers,
                              int levels) {
  return make_texture(GL_TEXTURE_2D_ARRAY, internal_format,
                      {.width = width, .height = height, .depth = layers, .levels = levels});
}

Texture make_texture_3d(GLenum internal_format, int width, int height, int depth, int levels) {
  return make_texture(
      GL_TEXTURE_3D, internal_format,
      {.width = width, .height = height, .depth = depth, .levels = levels, .depth_halves = true});
}

Renderbuffer make_renderbuffer(GLenum internal_format, int width, int height, int samples) {
  const std::int64_t bytes = texture_storage_bytes(
      internal_format, {.width = width, .height = height, .samples = samples});
  GLuint id = 0;
  glCreateRenderbuffers(1, &id);
  glNamedRenderbufferStorageMultisample(id, samples, internal_format, width, height);
  meter_storage(StorageKind::RenderbufferName, id, bytes);
  return Renderbuffer(id);
}

Texture make_depth_texture(GLenum internal_format, int width, int height, bool compare) {
  Texture t = make_texture_2d(internal_format, width, height);
  if (compare) {
    glTextureParameteri(t.get(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(t.get(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  }
  // Outside the map counts as lit (depth 1 = farthest).
  glTextureParameteri(t.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  glTextureParameteri(t.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  const float border[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  glTextureParameterfv(t.get(), GL_TEXTURE_BORDER_COLOR, border);
  return t;
}

Sampler make_sampler(bool linear, bool compare, float border) {
  GLuint id = 0;
  glCreateSamplers(1, &id);
  const GLint filter = linear ? GL_LINEAR : GL_NEAREST;
  glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, filter);
  glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER, filter);
  glSamplerParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  glSamplerParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  const float b[4] = {border, border, border, border};
  glSamplerParameterfv(id, GL_TEXTURE_BORDER_COLOR, b);
  if (compare) {
    glSamplerParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glSamplerParameteri(id, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  }
  return Sampler(id);
}

Framebuffer make_framebuffer(std::initializer_list<GLuint> colors, GLuint depth,
                             GLenum depth_attachment) {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  Framebuffer fb(id);
  GLenum draw_buffers[8];
  GLsizei n = 0;
  for (GLuint c : colors) {
    const GLenum attachment = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(n);
    glNamedFramebufferTexture(id, attachment, c, 0);
    draw_buffers[n++] = attachment;
  }
  if (n > 0)
    glNamedFramebufferDrawBuffers(id, n, draw_buffers);
  else
    glNamedFramebufferDrawBuffer(id, GL_NONE);
  if (depth != 0) glNamedFramebufferTexture(id, depth_attachment, depth, 0);
  const GLenum status = glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw JobError("framebuffer incomplete (status 0x" + std::to_string(status) + ")");
  return fb;
}

Buffer make_buffer(GLsizeiptr bytes, const void* data, GLbitfield flags) {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  glNamedBufferStorage(id, bytes, data, flags);
  meter_storage(StorageKind::BufferName, id, bytes);
  return Buffer(id);
}

Buffer make_stream_buffer() {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  meter_storage(StorageKind::BufferName, id, 0);
  return Buffer(id);
}

void set_buffer_data(const Buffer& buffer, GLsizeiptr bytes, const void* data, GLenum usage) {
  glNamedBufferData(buffer.get(), bytes, data, usage);
  meter_restorage(StorageKind::BufferName, buffer.get(), bytes);
}

namespace {
// One per context; contexts are used one at a time, and a new one forgets it.
GLuint g_empty_vao = 0;
}  // namespace

GLuint empty_vertex_array() {
  if (g_empty_vao == 0) glCreateVertexArrays(1, &g_empty_vao);
  return g_empty_vao;
}

void forget_context_objects() { g_empty_vao = 0; }

void draw_fullscreen_triangle() {
  glBindVertexArray(empty_vertex_array());
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void reset_state() {
  glDisable(GL_BLEND);
  // A technique that failed mid-pass may have left a blend equation (MAX)
  // that the next technique's additive passes would silently inherit.
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ZERO);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_STENCIL_TEST);
  glStencilFunc(GL_ALWAYS, 0, 0xff);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glDepthFunc(GL_LESS);
  glFrontFace(GL_CCW);
  glCullFace(GL_BACK);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_DEPTH_CLAMP);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glStencilMask(0xff);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  // The harness reads V back with glGetTextureImage: a pixel pack buffer,
  // row length, skips or read clamp left behind would make it fail, or
  // read rows shifted or values clamped into [0, 1] without an error.
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  for (const GLenum store :
       {GL_PACK_ROW_LENGTH, GL_PACK_IMAGE_HEIGHT, GL_PACK_SKIP_ROWS, GL_PACK_SKIP_PIXELS,
        GL_PACK_SKIP_IMAGES, GL_PACK_SWAP_BYTES, GL_PACK_LSB_FIRST, GL_UNPACK_ROW_LENGTH,
        GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_PIXELS, GL_UNPACK_SKIP_IMAGES,
        GL_UNPACK_SWAP_BYTES, GL_UNPACK_LSB_FIRST})
    glPixelStorei(store, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glClampColor(GL_CLAMP_READ_COLOR, GL_FIXED_ONLY);
}

const char* const kFullscreenVertexShader = R"(#version 450 core
out vec2 uv;
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  uv = p;
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

}  // namespace sb::gl
