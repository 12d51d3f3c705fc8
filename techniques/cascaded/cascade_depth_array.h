#pragma once
// The cascades' depth maps: one 2D array texture, a layer per cascade, each
// drawn with its cascade's orthographic view from the sun (the kit's
// DepthMap draws a single 2D map; a cascaded lookup needs every cascade in
// one shader, and an array keeps each layer's border its own, where an atlas
// would let filter taps read the neighbouring cascade).
//
//   GL     made in prepare() (a texture, a framebuffer per layer, two
//          programs); render() leaves the last layer's framebuffer bound,
//          the viewport at size×size, GL_DEPTH_TEST on with GL_LESS, and
//          turns polygon offset and face culling off again;
//   cost   per cascade one depth clear and one draw per caster mesh; memory
//          layers × size² × bytes per texel of the depth format (metered:
//          technique.gpu_bytes).
#include <vector>

#include "common/depth_pass.h"
#include "gl/gpu_scene.h"
#include "gl/objects.h"
#include "gl/program.h"

namespace sb::techniques::cascaded {

class CascadeDepthArray {
 public:
  CascadeDepthArray() = default;
  CascadeDepthArray(int size, int layers, GLenum depth_format);
  // Draws the casters into `layer` with `light_view_projection` (window
  // depths in [0,1], 1 where nothing was drawn). Alpha-tested casters
  // discard their holes; only closed casters are culled (`cull`).
  void render(const gl::GpuScene& gpu, int layer, const glm::mat4& light_view_projection,
              CullMode cull, DepthBias bias) const;
  GLuint texture() const { return texture_.get(); }
  int size() const { return size_; }

 private:
  int size_ = 0;
  gl::Texture texture_;
  std::vector<gl::Framebuffer> framebuffers_;
  gl::Program program_;
  gl::Program masked_program_;
};

}  // namespace sb::techniques::cascaded
