#pragma once
// two_map_bound's "penumbra buffer" (Shypula 2008 ch. 8, option 2: a
// gradient between two silhouette sets), in the penumbra apex's map space.
//
// Every silhouette edge seen from the penumbra apex A bounds the shadow of A
// (the outer boundary of the penumbra); the same edge seen from the umbra
// apex E casts the inner boundary. Drawn into a buffer of the map's size,
// each edge's band covers the occluder's side of its projection, as wide as
// the inner boundary can lie inside it on the farthest receiver; each texel
// keeps, by depth test, the nearest edge: the edge point q whose image is
// nearest and that distance d (A's image-plane units). The lookup finds,
// for a penumbra pixel at axis depth z_r, where E's shadow of q falls in
// A's image, and so the penumbra's width Δ there: V = 1 − d / Δ (linear from
// the lit side to the umbra). Without an umbra apex, E is the light's
// centre: the gradient spans the outer penumbra only.
#include "common/light_frustum.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "plugin/technique.h"

namespace sb::techniques::two_map {

// GLSL: uniforms `apex_view` (A's view), `inner_apex` (E, world),
// `light_centre`, `light_axis`; `vec2 apex_image(vec3 world)` (A's image
// plane, tan units) and `vec2 inner_image(vec3 q, float zr)`: where E's
// shadow of q falls on a receiver at axis depth zr, in A's image.
extern const char* const kInnerImageGlsl;

class PenumbraBuffer {
 public:
  PenumbraBuffer() = default;
  explicit PenumbraBuffer(int size);
  // The bands of the casters' silhouette seen from `apex` (its frustum
  // `frustum`), towards the inner apex `inner_apex`.
  void render(const plugin::FrameInputs& in, const LightFrustum& frustum,
              const glm::vec3& inner_apex);
  // RGBA32F: xyz the edge point q (world), w the image distance d; w < 0
  // where no band reached.
  GLuint texture() const { return texture_.get(); }

 private:
  int size_ = 0;
  gl::Texture texture_;
  gl::Texture depth_;
  gl::Framebuffer framebuffer_;
  gl::Program program_;
};

}  // namespace sb::techniques::two_map
