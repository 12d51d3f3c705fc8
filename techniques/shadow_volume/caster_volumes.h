#pragma once
// The stencil shadow volumes of every closed caster, from the light's
// centre, shared by the techniques that need an umbra: shadow_volume and
// penumbra_wedges (whose umbra pass this is).
//
// Per caster and frame: z-fail or z-pass (`auto` decides per caster with
// near_plane_pyramid.h); on the CPU path, its silhouette (silhouette.h) and
// its volume's triangles (volume_mesh.h), uploaded as one stream and drawn
// with one glMultiDrawArrays per counting rule. The GPU path (a geometry
// shader over edge adjacency) lives in shadow_volume.cpp; it uses the
// casters and their z-fail choice from here.
#include <string>
#include <vector>

#include "core/params.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "plugin/technique.h"
#include "shadow_volume/silhouette.h"
#include "shadow_volume/volume_mesh.h"

namespace sb::techniques::shadow_volume {

// The parameters that the volume techniques share, with one help text for
// the silhouette's mode: "silhouette", "epsilon" and "smooth_offset".
std::vector<core::ParamSpec> silhouette_params(const std::string& silhouette_help);
SilhouetteSettings silhouette_settings(const core::Params& p);

enum class CountMode { ZPass, ZFail, Auto };
// "zpass", "zfail" or "auto"; throws std::invalid_argument otherwise.
CountMode count_mode_from_string(const std::string& s);

// Stencil increments and decrements for a z-fail or a z-pass count.
void set_stencil_ops(bool zfail);

// GL state for counting volumes into the stencil of the bound framebuffer
// (whose depth is the G-buffer's): stencil cleared, depth test on without
// writes, depth clamp (the volumes reach infinity), no colour writes.
// `offset` is glPolygonOffset's units (0: none).
void begin_stencil_count(float offset);
void end_stencil_count();

// Fragment shader that writes V = 0 where it is drawn (stencil count non-zero)
// on geometry, and 1 on background; use with gl::kFullscreenVertexShader
// and the G-buffer position texture on unit 0.
extern const char* const kStencilResolveFragment;

// Vertex shader of a volume stream: homogeneous positions (w = 0 at
// infinity) at attribute 0, times the uniform `view_projection`.
extern const char* const kVolumeVertex;

// V from the stencil count in the visibility framebuffer (bound): 1 where
// the count is zero, kStencilResolveFragment's V elsewhere; ends the
// stencil test. `resolve` is a program made of kStencilResolveFragment.
void resolve_stencil(const plugin::FrameInputs& in, const gl::Program& resolve);

// A vertex array reading homogeneous positions (vec4, attribute 0) from a
// buffer of its own, filled every frame: the volumes' vertex stream.
void make_vec4_stream(gl::Buffer& buffer, gl::VertexArray& vao);

class CasterVolumes {
 public:
  struct Caster {
    size_t mesh = 0;  // index into Scene::meshes
    core::Bounds box;
    SilhouetteMesh shape;  // CPU path only
    bool zfail = true;
    VolumeVertices::Range range;
  };

  CasterVolumes(CountMode mode, bool cpu, const SilhouetteSettings& settings)
      : mode_(mode), cpu_(cpu), settings_(settings) {}

  // Scene data only: each caster's box and, on the CPU path, its triangles
  // and edges (need::kCasterEdges), the volume program and the vertex stream.
  void prepare(const plugin::FrameInputs& in);
  // Per caster, this frame: z-fail or z-pass (the camera and light may move).
  void choose_zfail(const plugin::FrameInputs& in);
  // CPU path: silhouettes from `light` (choose_zfail first).
  void find_silhouettes(const glm::vec3& light);
  // CPU path: the volumes' triangles, and their upload.
  void extrude(const glm::vec3& light);
  void upload();
  // CPU path: draws the casters counted by the given rule (stencil ops set
  // by the caller), with the program bound here.
  void draw(const plugin::FrameInputs& in, bool zfail);
  // CPU path: one caster's volume alone, with its own counting rule's
  // stencil ops; with `program` (vertex input: location 0, vec4; its
  // uniforms set by the caller) instead of the volumes' own.
  void draw_caster(const plugin::FrameInputs& in, size_t caster,
                   const gl::Program* program = nullptr);

  const std::vector<Caster>& casters() const { return casters_; }
  const std::vector<Silhouette>& silhouettes() const { return silhouettes_; }

 private:
  CountMode mode_;
  bool cpu_;
  SilhouetteSettings settings_;
  std::vector<Caster> casters_;
  std::vector<Silhouette> silhouettes_;
  VolumeVertices mesh_;
  std::vector<GLint> firsts_;
  std::vector<GLsizei> counts_;
  gl::Program program_;
  gl::Buffer vertices_;
  gl::VertexArray vao_;
};

}  // namespace sb::techniques::shadow_volume
