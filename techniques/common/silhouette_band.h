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
//          kSilhouetteBandVertexGlsl;
//   out    6 vertices per caster edge drawn as GL_TRIANGLES into whatever
//          framebuffer is bound, with the caller's state (depth, blending);
//   GL     draw_silhouette_bands() binds the edge buffer to shader-storage
//          binding 0 and an empty vertex array; nothing else;
//   cost   6 vertex-shader runs per caster edge, silhouette or not; no CPU
//          work, no upload.
#include "common/light_frustum.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "plugin/technique.h"

namespace sb::techniques {

// GLSL for vertex shaders (binding 0: the edge buffer):
//   struct Edge, edges[]          the buffer's records
//   bool on_silhouette(Edge e, vec3 l)   seen from the point l
//   vec3 into_lit_face(Edge e, vec3 l)   world direction from the edge into
//       its face that l sees: the occluder's side of the silhouette
//   vec2 outward_normal(vec2 a, vec2 b, vec2 inside)   the segment's unit
//       normal away from `inside`, or vec2(0) when degenerate
//   vec2 band_corner(vec2 a, vec2 b, float r, vec2 outward, int k)
//       corner k (0..5, two triangles) of the rectangle that holds every
//       point within r of the segment a–b (a capsule's bounding box), or
//       only its half on the side of `outward` when that is not vec2(0)
//   const int kBandVertices = 6
extern const char* const kSilhouetteBandVertexGlsl;

// GLSL for fragment shaders:
//   float segment_param(vec2 p, vec2 a, vec2 b)   the closest point's t ∈ [0,1]
//   float light_ratio(vec2 p, vec2 a, vec2 b, vec2 hu, vec2 hv,
//                     float sa, float sb, out float t)
//       the least g(t) / s(t) over the segment a–b, where g(t) is the
//       light-shaped distance of p from the segment's point t: the smallest
//       g with p in that point grown by g times the light's shape, the
//       parallelogram of half axes hu, hv (not parallel, and not orthogonal
//       in general: a tilted receiver or a rotated light projects the
//       rectangle to a parallelogram); s(t) = mix(sa, sb, t); and t attains it.
//       An occluder point at depth z_o casts the light's shape scaled by
//       s = 1/z_o − 1/z_r (image plane) onto a receiver at depth z_r, so p
//       is in the edge's penumbra iff the ratio is below 1, and 1 − ratio is
//       the linear darkness: parallelograms at the edge's ends ("cones"), the
//       light's support function wide along it ("sheets"), as they must be.
//   mat2 light_coordinates(vec2 hu, vec2 hv)
//       the matrix taking v to its (α, β) with v = α·hu + β·hv
//   float light_distance_at(vec2 p, vec2 a, vec2 b, vec2 hu, vec2 hv, float t)
//       g(t) alone
//   vec2 fragment_image()   the fragment's point in the map's image plane
//       (tan units), from gl_FragCoord rather than a varying: across a wide
//       band an interpolated varying loses the precision a texel needs.
//       Its uniforms are set by set_fragment_image_uniforms().
extern const char* const kSilhouetteBandFragmentGlsl;

// The uniforms of fragment_image() for a map of `size` texels drawn with
// `frustum`'s (possibly off-axis) projection.
void set_fragment_image_uniforms(const gl::Program& program, const LightFrustum& frustum, int size);

// Binds the edge buffer and draws 6 vertices per edge with the bound program.
// cost: 6 vertex-shader runs per caster edge, silhouette or not; no CPU work.
void draw_silhouette_bands(const plugin::FrameInputs& in);

}  // namespace sb::techniques
