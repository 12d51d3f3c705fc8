#pragma once
// Renders the casters into the slabs' binary occlusion textures in one pass,
// as Eisemann & Décoret do: four slabs per RGBA8 texture, one texture per
// render target (MRT), each fragment writing 1 into the channel of the slab
// its depth falls in, blended with MAX so that overlapping fragments OR.
// Alpha-masked texels are holes, as for every other pass.
//
// Which faces: a closed caster's light-facing faces alone, by default. They
// cover the caster's shadow once, like a height field seen from the light;
// with every face, a plate's top and bottom land in two slabs, and the
// probabilistic product (1 − α)² turns its straight penumbra ramp into a
// parabola (plates scene, 16 slices: penumbra RMSE 0.119). Open and
// double-sided casters (leaves) keep every face.
//
// Thin-occluder fix (Eisemann & Décoret 2008, §3.4, light leaks): each
// texture is projected onto its successor, the next slab away from the
// light. Both projections (slicing.h) map a point to the same texel
// whichever slab's plane it is drawn on, so that projection is each
// fragment marking the next slab as well. A surface that slopes across a
// slab boundary then covers, in the farther slab, the gap that a slanted
// shadow ray slips through between its two pieces; the copy lies behind
// the surface it comes from, which never reads it. The price: a slab's
// content counts twice for points beyond both, and the product of
// (1 − α) darkens where it meets itself.
//
// (An earlier reading here marked the slab towards the light instead, so
// that a point skipping its own slab would count an occluder just above
// it; a lit surface then met its own copy in the slab it fades in. On the
// sphere grid, four jeeps and two trees it lost to no fix at all, or tied
// (docs/occlusion_textures.md), and is gone.)
#include <vector>

#include "gl/gpu_scene.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "occlusion_texture/slicing.h"

namespace sb::techniques::occlusion_texture {

class SlabRasterizer {
 public:
  SlabRasterizer() = default;
  // `targets`: ceil(slabs / 4) RGBA8 textures of size × size (level 0 is drawn).
  SlabRasterizer(int slabs, int size, const std::vector<GLuint>& targets, bool light_facing_only,
                 bool thin_occluder_fix);
  void render(const gl::GpuScene& gpu, const Slicing& slicing) const;

 private:
  int size_ = 0;
  int textures_ = 0;
  bool light_facing_only_ = true;
  bool thin_occluder_fix_ = false;
  gl::Framebuffer framebuffer_;
  gl::Program program_;
};

// The uniforms every pass that maps the light's frame to texture space
// reads (light_center, light_u, light_v, light_n, z0, thickness, origin,
// scale, proj_a, proj_b); kSlicingUniformsGlsl declares them, with
// light_half (the light's half sizes) for the passes that need it.
void set_slicing_uniforms(const gl::Program& program, const Slicing& slicing);
extern const char* const kSlicingUniformsGlsl;

}  // namespace sb::techniques::occlusion_texture
