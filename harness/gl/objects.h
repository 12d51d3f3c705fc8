#pragma once
// Move-only owners of GL object names, and the makers of textures,
// renderbuffers and buffers: storage made through them is what a technique's
// technique.gpu_bytes counts (gl/allocation_meter.h); storage a plugin makes
// with raw GL calls is not counted.
#include <utility>

#include "gl/gl.h"

namespace sb::gl {

template <void (*Delete)(GLuint)>
class Handle {
 public:
  Handle() = default;
  explicit Handle(GLuint id) : id_(id) {}
  ~Handle() { reset(); }
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  GLuint get() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_ != 0) Delete(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

// Deleting a texture, renderbuffer or buffer releases its metered bytes.
void delete_texture(GLuint id);
void delete_buffer(GLuint id);
void delete_renderbuffer(GLuint id);
inline void delete_framebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
inline void delete_vertex_array(GLuint id) { glDeleteVertexArrays(1, &id); }
inline void delete_sampler(GLuint id) { glDeleteSamplers(1, &id); }
inline void delete_program(GLuint id) { glDeleteProgram(id); }

using Texture = Handle<delete_texture>;
using Buffer = Handle<delete_buffer>;
using Framebuffer = Handle<delete_framebuffer>;
using VertexArray = Handle<delete_vertex_array>;
using Sampler = Handle<delete_sampler>;
using Renderbuffer = Handle<delete_renderbuffer>;

// A 2D texture with immutable storage, nearest filtering, clamped edges.
Texture make_texture_2d(GLenum internal_format, int width, int height);
// The same with `levels` mip levels (filtering as above: a caller that
// samples the chain sets its own minification filter).
Texture make_mipmapped_texture_2d(GLenum internal_format, int width, int height, int levels);
// A 2D array texture of `layers` layers, filtering and edges as above.
Texture make_texture_2d_array(GLenum internal_format, int width, int height, int layers,
                              int levels = 1);
// A 3D texture, filtering and edges as above; its depth halves with each level.
Texture make_texture_3d(GLenum internal_format, int width, int height, int depth, int levels = 1);
// A renderbuffer; `samples` 0 is single-sampled.
Renderbuffer make_renderbuffer(GLenum internal_format, int width, int height, int samples = 0);
// A depth texture usable as sampler2DShadow (compare mode on) or plain.
Texture make_depth_texture(GLenum internal_format, int width, int height, bool compare);
// A sampler object: lets one texture be read two ways (e.g. a depth map as
// sampler2DShadow and as raw depths). `compare` turns on GL_LEQUAL
// reference comparison; outside the texture reads `border`.
Sampler make_sampler(bool linear, bool compare, float border);
// Framebuffer with the given colour attachments (0 = none) and depth(-stencil).
Framebuffer make_framebuffer(std::initializer_list<GLuint> colors, GLuint depth,
                             GLenum depth_attachment = GL_DEPTH_ATTACHMENT);
// A buffer with immutable storage of `bytes`.
Buffer make_buffer(GLsizeiptr bytes, const void* data, GLbitfield flags = 0);
// A buffer with mutable storage, empty until set_buffer_data(): a stream
// whose size changes from frame to frame.
Buffer make_stream_buffer();
// Replaces the storage of a make_stream_buffer() buffer with `bytes` of
// `data` (glNamedBufferData): the buffer counts its latest size.
void set_buffer_data(const Buffer& buffer, GLsizeiptr bytes, const void* data, GLenum usage);

// A vertex array with no attributes, for draws that build their vertices
// from gl_VertexID (one per context).
GLuint empty_vertex_array();
// Draws one triangle covering the viewport (no vertex buffer: uses gl_VertexID).
void draw_fullscreen_triangle();
// Undoes whatever state a technique left behind: no blending (and the
// default blend equation and factors), scissor, stencil or depth test (and
// their default functions), culling (back faces, CCW front), polygon offset
// or depth clamp; every write mask on; no program; the default framebuffer
// bound; no pixel pack or unpack buffer, the default pixel-store state and
// no read clamp (so that reading V back reads what the technique wrote).
void reset_state();
// Called when a context is made: drops names that belonged to the last one.
void forget_context_objects();
// Vertex shader for draw_fullscreen_triangle(); writes `uv` in [0,1]^2.
extern const char* const kFullscreenVertexShader;

}  // namespace sb::gl
