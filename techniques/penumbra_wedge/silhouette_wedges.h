#pragma once
// What both wedge techniques build every frame before they draw: the light
// centre's silhouettes and umbra volumes (shadow_volume/caster_volumes.h),
// one wedge per silhouette edge (wedge_geometry.h), and their upload
// (wedge_stream.h), each a timed pass: silhouettes, volumes, wedges, upload.
#include <vector>

#include "core/params.h"
#include "gl/pass_timer.h"
#include "penumbra_wedge/wedge_geometry.h"
#include "penumbra_wedge/wedge_stream.h"
#include "plugin/technique.h"
#include "shadow_volume/caster_volumes.h"

namespace sb::techniques::penumbra_wedge {

class SilhouetteWedges {
 public:
  // Reads umbra_params() (wedge_variants.h).
  explicit SilhouetteWedges(const core::Params& p);
  void prepare(const plugin::FrameInputs& in);
  void build(const plugin::FrameInputs& in, gl::PassTimer& timer);

  const LightFrame& frame() const { return frame_; }
  shadow_volume::CasterVolumes& volumes() { return volumes_; }
  const WedgeBatch& batch() const { return batch_; }
  // Per caster (volumes().casters()' order): its wedges' indices; their
  // vertices have the same numbers (every index is its own vertex).
  const std::vector<IndexRange>& caster_wedges() const { return caster_wedges_; }
  const WedgeStream& stream() const { return stream_; }

 private:
  shadow_volume::CasterVolumes volumes_;
  LightFrame frame_;
  WedgeBatch batch_;
  std::vector<IndexRange> caster_wedges_;
  WedgeStream stream_;
};

// GL state for drawing wedge hulls into a framebuffer with the G-buffer's
// depth: back faces only (each pixel once per wedge, at the hull's exit),
// depth test GEQUAL without writes (a surface behind the exit is outside the
// wedge), depth clamp (the hull may reach past the far plane).
void begin_hull_draw();
void end_hull_draw();

// A view of the G-buffer's depth-stencil texture that shaders read as
// stencil counts (usampler2D; 8-bit counts, wrapped).
gl::Texture make_stencil_view(GLuint depth_stencil);

// GLSL: the signed count from such a view's texel.
extern const char* const kStencilCountGlsl;

}  // namespace sb::techniques::penumbra_wedge
