#pragma once
// The contract between the harness and a shadow technique.
//
// A technique computes VISIBILITY only: for every camera pixel, the fraction
// of the area light that the pixel's surface point sees, written to an R32F
// target the harness owns. The surface points are the G-buffer's world
// positions, the same ones the ray-traced reference uses, so primary
// visibility never pollutes the error. Shading is shared by all techniques.
#include <glm/glm.hpp>
#include <memory>
#include <string>

#include "core/params.h"
#include "core/scene.h"
#include "gl/gl.h"
#include "gl/pass_timer.h"
#include "plugin/derived_data.h"
#include "plugin/needs.h"

namespace sb::gl {
class GpuScene;
}  // namespace sb::gl

namespace sb::plugin {

// Everything a technique may read for one (scene, resolution).
struct FrameInputs {
  int width = 0;
  int height = 0;
  const core::Scene* scene = nullptr;
  const gl::GpuScene* gpu = nullptr;
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
  glm::mat4 view_projection{1.0f};
  // G-buffer (camera view): world position (RGBA32F, w = 1 on geometry, 0 on
  // background) and the triangle's geometric normal (RGBA32F; w = 1 on a
  // caster, 0 on a mesh that casts no shadow).
  GLuint gbuffer_position = 0;
  GLuint gbuffer_normal = 0;
  // The shading normal (interpolated, RGBA32F) and albedo (RGBA8, texture ×
  // material colour) at the same pixels, for techniques that filter or weigh
  // by them.
  GLuint gbuffer_shading_normal = 0;
  GLuint gbuffer_albedo = 0;
  // The plane that receives every caster's shadow, n·x + d = 0 with n towards
  // the casters: set when the technique declared need::kPlanarReceiver
  // (its job is skipped when the scene has none).
  bool has_receiver_plane = false;
  glm::vec4 receiver_plane{0.0f};
  // The G-buffer pass's depth-stencil (D24S8) texture, also attached to the
  // visibility framebuffer, so stencil techniques can test against it.
  GLuint depth_stencil = 0;
  // R32F visibility colour + depth_stencil. Techniques must write every pixel
  // (V = 1 on background).
  GLuint visibility_framebuffer = 0;
  GLuint visibility_texture = 0;
  // Everything derived for the technique's needs (plugin/needs.h), CPU and
  // GPU, by need name: derived->get<SilhouetteEdges>(need::kSilhouetteEdges).
  const DerivedData* derived = nullptr;
};

// Made by TechniqueInfo::create from its Params. The constructor reads every
// parameter the technique declares, whatever the mode, and makes no GL call:
// `validate`, `plan` and `run` create each variant without a GL context to
// warn about a declared parameter it never reads (config/unread_params.h).
// GL objects are made in prepare().
class Technique {
 public:
  virtual ~Technique() = default;
  // Once per (scene, resolution), untimed. It may compile shaders, allocate
  // targets and upload or derive immutable scene data (geometry, textures),
  // and precompute what depends on the technique's parameters only, such as
  // sample offsets in the light's own (u, v) frame. It must not do anything
  // that depends on the light's pose or the camera (fitting a light
  // frustum, placing light samples in the world, light-derived uniforms):
  // an engine does that every frame, so here it belongs in render(), where
  // it is timed; done in prepare() it would hide its cost from the timed
  // frames, and be stale if the light moved. tests/techniques/
  // test_timing_contract.cpp moves the light after prepare() and checks
  // that the next frame equals one from a technique prepared under the
  // moved light.
  virtual void prepare(const FrameInputs& in) = 0;
  // One frame, timed. Every GL command belongs to a named pass of `timer`,
  // e.g. auto pass = timer.scope("shadow_map");
  //
  // The technique's time is everything render() does, CPU and GPU, from its
  // call to the end of its last GL command, on every kind of bracket
  // (gl/pass_timer.h); CPU work needs no marking:
  // - cpu_glfinish (llvmpipe, software rasterisers): glFinish, then a steady
  //   clock until a glFinish after render() returns. CPU work, command
  //   submission, read-back waits and rasterisation all count, one after
  //   another.
  // - gl_timestamp_query (GPUs): from the GL's clock when render() is called
  //   (or when the GPU finishes the G-buffer bracket's commands, if later) to
  //   a GL timestamp after its last command, and never less than the CPU's
  //   time in render(). CPU work (silhouettes, read-backs, reconstruction)
  //   counts as on llvmpipe; GPU work that runs while the CPU works counts
  //   once, not twice.
  // GL commands still running on the GPU when render() returns count (the
  // end waits for them); work moved out of render() does not, so none may
  // be: no fence waited on in the next frame, no CPU work on a thread that
  // outlives the call.
  virtual void render(const FrameInputs& in, gl::PassTimer& timer) = 0;
};

}  // namespace sb::plugin
