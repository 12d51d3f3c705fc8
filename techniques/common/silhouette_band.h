#pragma once
// Bands around silhouette edges, drawn straight from the harness's edge
// buffer (need::kSilhouetteEdges, plugin/silhouette_edges.h): the geometry of
// plateaus, penumbra maps and smoothies. One draw of 6 vertices per edge of
// the casters; the vertex shader finds whether its edge is on the silhouette
// from the light's centre and emits the two triangles of a quad around it,
// or a degenerate triangle when it is not. Nothing is built on the CPU and
// nothing is uploaded per frame.
//
// What the kit guarantees here (shadowbench::shadow_kit, installed):
//   in     the edge buffer of need::kSilhouetteEdges, which the technique
//          must declare (FrameInputs::derived holds it only then), and the
//          program the caller bound, its vertex shader built on
//          kSilhouetteBandVertexGlsl (common/silhouette_band_glsl.h);
//   out    6 vertices per caster edge drawn as GL_TRIANGLES into whatever
//          framebuffer is bound, with the caller's state (depth, blending);
//   GL     draw_silhouette_bands() binds the edge buffer to shader-storage
//          binding 0 and an empty vertex array; nothing else;
//   cost   6 vertex-shader runs per caster edge, silhouette or not; no CPU
//          work, no upload.
#include "common/light_frustum.h"
#include "common/silhouette_band_glsl.h"  // kSilhouetteBandVertexGlsl, ...FragmentGlsl
#include "gl/objects.h"
#include "gl/program.h"
#include "plugin/technique.h"

namespace sb::techniques {

// The uniforms of fragment_image() for a map of `size` texels drawn with
// `frustum`'s (possibly off-axis) projection.
void set_fragment_image_uniforms(const gl::Program& program, const LightFrustum& frustum, int size);

// Binds the edge buffer and draws 6 vertices per edge with the bound program.
// cost: 6 vertex-shader runs per caster edge, silhouette or not; no CPU work.
void draw_silhouette_bands(const plugin::FrameInputs& in);

}  // namespace sb::techniques
