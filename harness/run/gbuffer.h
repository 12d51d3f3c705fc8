#pragma once
// Shared passes, never charged to a technique: the G-buffer (camera view) and
// the shading pass that turns visibility into a picture.
//
// The G-buffer is rendered once per (scene, resolution): the scene and the
// camera do not move between frames, so every frame's G-buffer would be the
// same bytes. On llvmpipe re-rendering it cost more than most techniques
// (27-35 ms at 800×600 on the sphere grid, mostly vertex and geometry shading
// on the driver's one draw thread; docs/performance.md). A frame instead
// restores the one attachment a technique may write, the depth-stencil
// (stencil techniques count in it), from the copy taken after the pass; the
// colour attachments are read-only to techniques (tests/gl/
// test_gbuffer_untouched.cpp checks every registered technique).
#include "core/image.h"
#include "gl/gpu_scene.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "plugin/technique.h"

namespace sb::run {

class FrameTargets {
 public:
  FrameTargets(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }

  // Rasterises the camera view: world position, geometric normal, shading
  // normal, albedo, depth-stencil; then keeps a copy of the depth-stencil.
  void render_gbuffer(const gl::GpuScene& gpu, const glm::mat4& view_projection);
  // Puts back the depth-stencil render_gbuffer() left: what a frame starts
  // from, whatever the previous frame's technique did to its stencil.
  void restore_gbuffer();
  // Shades with the current visibility: linear radiance → display value
  // (gamma 2.2), written to the RGBA32F shaded target.
  void render_shading(const core::Scene& scene);

  plugin::FrameInputs inputs(const core::Scene& scene, const gl::GpuScene& gpu,
                             const glm::mat4& view, const glm::mat4& projection) const;

  core::ImageF read_positions() const;          // 4 channels
  core::ImageF read_geometric_normals() const;  // 3 channels
  // 1 where the surface belongs to a mesh that casts no shadow, else 0.
  core::ImageF read_receiver_mask() const;
  core::ImageF read_visibility() const;  // 1 channel
  core::ImageF read_shaded() const;      // 3 channels
  // Overwrites the visibility target (used to shade the reference).
  void upload_visibility(const core::ImageF& v);

 private:
  int width_;
  int height_;
  gl::Texture position_, geometric_normal_, shading_normal_, albedo_, depth_stencil_;
  gl::Texture pristine_depth_stencil_;  // depth_stencil_ as the G-buffer pass left it
  gl::Texture visibility_, shaded_;
  gl::Framebuffer gbuffer_fb_, visibility_fb_, shaded_fb_;
  gl::Program gbuffer_program_, shading_program_;
};

// Reads a texture's level 0 into an image, flipping rows so row 0 is on top.
core::ImageF read_texture(GLuint texture, int width, int height, int channels);

}  // namespace sb::run
