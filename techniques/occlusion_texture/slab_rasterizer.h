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
// Thin-occluder fix: a caster's point skips its own slab and fades the one
// in front of it in (slicing.h, self_shadow_offset), so an occluder less
// than a slab above a caster's surface, such as a fender over a body panel,
// is partly lost. With the fix every face also marks the next slab towards
// the light, so such points count it in full; the price is that the copy
// sits a slab too far from the receiver (too wide a penumbra), and that a
// lit surface meets its own copy in the slab it fades in, and darkens.
#include <vector>

#include "gl/gpu_scene.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "occlusion_texture/slicing.h"

namespace sb::occlusion {

class SlabRasterizer {
 public:
  SlabRasterizer() = default;
  // `targets`: ceil(slabs / 4) RGBA8 textures of size × size (level 0 is drawn).
  SlabRasterizer(int slabs, int size, const std::vector<GLuint>& targets, bool light_facing_only,
                 bool thin_occluder_fix);
  void render(const GpuScene& gpu, const Slicing& slicing) const;

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

}  // namespace sb::occlusion
