#pragma once
// The wedges of a frame on the GPU: hull vertices and indices as dynamic
// streams, and the wedge records as a shader storage buffer (binding 0) that
// fragments index by their wedge's number (vertex attribute 1, flat).
#include "gl/objects.h"
#include "gl/program.h"
#include "penumbra_wedge/wedge_geometry.h"

namespace sb::techniques::penumbra_wedge {

class WedgeStream {
 public:
  // GL objects only; call with a context current (in prepare()).
  void create();
  // Orphans and refills the three buffers.
  void upload(const WedgeBatch& batch);
  // Binds the vertex array and the records, for draw().
  void bind() const;
  // Draws a range of the indices (the whole batch by default).
  static void draw(const IndexRange& range);

 private:
  gl::Buffer vertices_;
  gl::Buffer indices_;
  gl::Buffer records_;
  gl::VertexArray vao_;
};

// GLSL shared by the wedge techniques' fragment shaders (after #version):
// the wedge records, the light's frame, Lengyel's test, the edge projected
// from the point, and clipping against lines. See penumbra_wedges.cpp for
// the method.
extern const char* const kWedgeGlsl;

// How a silhouette loop (wound as the lit region, counter-clockwise seen
// from the light) turns when a point behind it projects it onto the
// light's plane, in the frame (u, v) with n = u × v towards the point.
constexpr float kLoopOrientation = -1.0f;

// Sets kWedgeGlsl's uniforms, and view_projection, on `program`.
void set_wedge_uniforms(const gl::Program& program, const LightFrame& frame,
                        const glm::mat4& view_projection);

// The wedge techniques' vertex shader: world positions, the wedge's number
// passed on flat.
extern const char* const kWedgeVertex;

}  // namespace sb::techniques::penumbra_wedge
