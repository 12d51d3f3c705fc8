#pragma once
// The GLSL of silhouette bands (common/silhouette_band.h): the vertex
// shader's edge records and band geometry, and the fragment shader's
// distances to an edge measured in the light's shape. No #version: append
// them after one.
//
// Units: points and vectors named a, b, p, hu, hv are in the map's image
// plane (tan units: x/z and y/z in the light's view), unless a comment says
// world; l is a world point.
namespace sb::techniques {

// GLSL for vertex shaders (binding 0: the edge buffer of
// need::kSilhouetteEdges): the edge records, on_silhouette(),
// into_lit_face(), outward_normal(), band_corner().
inline constexpr const char* kSilhouetteBandVertexGlsl = R"glsl(
// One caster edge of the buffer (plugin/silhouette_edges.h), world units.
struct Edge {
  vec4 p0;       // xyz: first endpoint; w: mesh index
  vec4 p1;       // xyz: second endpoint; w: 1 with two faces, 0 with one
  vec4 plane_a;  // the face that winds p0 → p1, outward normal
  vec4 plane_b;  // the face across the edge
};
// The edge buffer, one record per caster edge (binding 0).
layout(std430, binding = 0) readonly buffer Edges { Edge edges[]; };
// Vertices drawn per edge: two triangles of a quad, or a degenerate one.
const int kBandVertices = 6;

// Whether the edge is on the silhouette seen from the world point l: its
// faces disagree on the side of l; an edge with one face (a boundary) is on
// the silhouette unless l lies in its face's plane.
// cost: two plane tests.
bool on_silhouette(Edge e, vec3 l) {
  float a = dot(e.plane_a, vec4(l, 1.0));
  if (e.p1.w == 0.0) return a != 0.0;
  float b = dot(e.plane_b, vec4(l, 1.0));
  return (a > 0.0) != (b > 0.0);
}

// The world direction from the edge into the face that l sees: the
// occluder's side of the silhouette. That face winds p0 → p1 if it is face a
// (else p1 → p0), so its inside is to the left of that direction about its
// outward normal. A one-face edge's face, lit from either side, lies to the
// left of p0 → p1 about its normal.
// units: world, not normalised.
vec3 into_lit_face(Edge e, vec3 l) {
  vec3 along = e.p1.xyz - e.p0.xyz;
  if (e.p1.w == 0.0 || dot(e.plane_a, vec4(l, 1.0)) > 0.0) return cross(e.plane_a.xyz, along);
  return cross(e.plane_b.xyz, -along);
}

// The segment's unit normal on the side away from `inside` (a direction
// into the occluder), or vec2(0) when either is degenerate.
vec2 outward_normal(vec2 a, vec2 b, vec2 inside) {
  vec2 d = b - a;
  vec2 across = vec2(-d.y, d.x);
  float side = dot(across, inside);
  if (dot(across, across) == 0.0 || side == 0.0) return vec2(0.0);
  return normalize(side > 0.0 ? -across : across);
}

// Corner k (0..5, two triangles) of the rectangle that holds every point
// within r of the segment a–b (a capsule's bounding box). outward: a unit
// vector to keep only that side of the segment (the band is then r wide on
// that side), or vec2(0) for both sides.
// units: those of a, b and r.
vec2 band_corner(vec2 a, vec2 b, float r, vec2 outward, int k) {
  vec2 d = b - a;
  float len = length(d);
  vec2 along = len > 0.0 ? d / len : vec2(1.0, 0.0);
  vec2 across = vec2(-along.y, along.x);
  bool one_side = outward != vec2(0.0);
  if (one_side && dot(across, outward) < 0.0) across = -across;
  // Corners 0..3: a-side low, b-side low, b-side high, a-side high.
  const int order[6] = int[6](0, 1, 2, 0, 2, 3);
  int c = order[k];
  vec2 end = (c == 1 || c == 2) ? b + r * along : a - r * along;
  float low = one_side ? 0.0 : -r;
  return end + ((c >= 2) ? r : low) * across;
}
)glsl";

// GLSL for fragment shaders: segment_param(), light_ratio(),
// light_coordinates(), light_distance_at(), fragment_image() and its
// uniforms (set by set_fragment_image_uniforms()).
inline constexpr const char* kSilhouetteBandFragmentGlsl = R"glsl(
// The parameter t in [0,1] of the point of the segment a–b closest to p.
float segment_param(vec2 p, vec2 a, vec2 b) {
  vec2 d = b - a;
  float len2 = dot(d, d);
  return len2 > 0.0 ? clamp(dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
}
// The root of c0 + c1·t, clamped to [0,1] (0 when c1 is 0).
float root_in_segment(float c0, float c1) { return c1 != 0.0 ? clamp(-c0 / c1, 0.0, 1.0) : 0.0; }
// The matrix taking v to its (α, β) with v = α·hu + β·hv. The light's axes,
// projected, are orthogonal only when the light faces the plane they are
// projected on or turns about no other axis (a tilted receiver or a rotated
// glTF light gives a parallelogram), so they are solved for, not read off by
// dot products.
mat2 light_coordinates(vec2 hu, vec2 hv) { return inverse(mat2(hu, hv)); }
// The least g(t) / s(t) over the segment a–b, and in t where it is attained:
// g(t) is the light-shaped distance of p from the segment's point t (the
// smallest g with p in that point grown by g times the parallelogram of half
// axes hu, hv), s(t) = mix(sa, sb, t). An occluder point at depth z_o casts
// the light's shape scaled by s = 1/z_o − 1/z_r (image plane) onto a
// receiver at depth z_r, so p is in the edge's penumbra iff the ratio is
// below 1, and 1 − ratio is the linear darkness.
// g(t) = max(|α(t)|, |β(t)|) for v = p − a − t(b − a) = α(t)·hu + β(t)·hv is
// convex and piecewise linear in t, with its breaks where a term is zero or
// the two terms are equal. On each linear piece g/s, s linear too, is
// monotone, so the least g/s over [0, 1] is at a break or an end. (The least
// g alone is not enough: g is flat over a range of t wherever the edge runs
// along a light axis, and the first point of that range may have s = 0.)
// cost: a 2×2 inverse and six candidates.
float light_ratio(vec2 p, vec2 a, vec2 b, vec2 hu, vec2 hv, float sa, float sb, out float t) {
  mat2 to_light = light_coordinates(hu, hv);
  vec2 c0 = to_light * (p - a), c1 = to_light * (a - b);
  float u0 = c0.x, u1 = c1.x, v0 = c0.y, v1 = c1.y;
  float candidates[6] = float[6](0.0, 1.0, root_in_segment(u0, u1), root_in_segment(v0, v1),
                                 root_in_segment(u0 - v0, u1 - v1),
                                 root_in_segment(u0 + v0, u1 + v1));
  float best = 1e38;
  t = 0.0;
  for (int i = 0; i < 6; ++i) {
    float c = candidates[i];
    float g = max(abs(u0 + c * u1), abs(v0 + c * v1));
    float s = mix(sa, sb, c);
    float ratio = s > 0.0 ? g / s : (g == 0.0 ? 0.0 : 1e38);
    if (ratio < best) {
      best = ratio;
      t = c;
    }
  }
  return best;
}
// fragment_image()'s uniforms, set by set_fragment_image_uniforms(): the
// projection's scale and off-axis shift, and the map's side in texels.
uniform vec4 image_from_ndc;  // image = (ndc + zw) / xy
uniform float map_size;
// The fragment's point in the map's image plane (tan units), from
// gl_FragCoord rather than a varying: across a wide band an interpolated
// varying loses the precision a texel needs.
vec2 fragment_image() {
  return (2.0 * gl_FragCoord.xy / map_size - 1.0 + image_from_ndc.zw) / image_from_ndc.xy;
}
// g(t) alone: the light-shaped distance of p from the segment's point t.
float light_distance_at(vec2 p, vec2 a, vec2 b, vec2 hu, vec2 hv, float t) {
  vec2 c = light_coordinates(hu, hv) * (p - mix(a, b, t));
  return max(abs(c.x), abs(c.y));
}
)glsl";

}  // namespace sb::techniques
