#pragma once
// The GLSL a lookup pass's lit_fraction() may call (common/map_lookup.h).
// MapLookupPass assembles one fragment shader from `#version 450 core`,
// kMapLookupInputsGlsl, kLightLookupGlsl, kLightDepthGlsl, the variant's
// lit_fraction() and its own main(). A pass of your own (a prefilter, a
// moments pass) may append kLightLookupGlsl and kLightDepthGlsl after a
// #version of its own.
//
// Units throughout: `t` is a point in the map's texture space (uv in [0,1]²,
// z the window depth in [0,1] the map stores, nonlinear in distance); a
// "view depth" is world units along the light's axis from its eye; world
// points and normals are the G-buffer's (world units).
//
// Each helper's comment: what it computes, then `units:` and `cost:` lines
// where they say something (a tap is one texture fetch).
namespace sb::techniques {

// The lookup pass's inputs, set by MapLookupPass::draw() and main() before
// lit_fraction() runs, and the helpers on them: shadow_tap(), clamp_unit(),
// receiver_view_depth(). Comes right after `#version 450 core`.
inline constexpr const char* kMapLookupInputsGlsl = R"glsl(
// The full-screen triangle's texture coordinate ([0,1]² over the camera image).
in vec2 uv;
// The G-buffer's world positions (w = 0 on the background) on unit 0 and
// geometric normals on unit 2; the depth map on unit 1 as a comparison
// sampler (1 lit, 0 shadowed; bilinear 2×2 PCF when the pass was made with
// linear_compare) and on unit 3 as raw window depths in [0,1] (nearest).
// Outside the map both read a border of depth 1 (lit).
layout(binding = 0) uniform sampler2D position_tex;
layout(binding = 1) uniform sampler2DShadow shadow_map;
layout(binding = 2) uniform sampler2D normal_tex;
layout(binding = 3) uniform sampler2D depth_map;
// The map's frustum (LightFrustum::view_projection and ::view), its eye
// (world units), the normal offset per unit distance from the eye
// (DepthMapSettings::normal_offset_per_distance; in world units when the
// map is orthographic, light_orthographic), whether taps compare
// against the receiver's plane (receiver_plane_bias), and the factor V is
// multiplied by (MapLookupPass::draw()'s `weight`).
uniform mat4 light_view_projection;
uniform mat4 light_view;
uniform vec3 light_point;
uniform float normal_offset;
uniform bool receiver_plane;
uniform float weight;
// The pass's output, V in [0,1] (R32F).
out float visibility;

// Set by main() before lit_fraction() runs: the receiver's point (moved
// along its normal by the normal offset; world units), its geometric normal,
// and d(window depth)/d(uv) of its tangent plane in the map (0 unless
// receiver_plane is on, or where the plane is seen edge-on).
vec3 receiver_world = vec3(0.0);
vec3 receiver_normal = vec3(0.0, 1.0, 0.0);
vec2 receiver_gradient = vec2(0.0);

// One depth comparison `offset` away from t: 1 lit, 0 shadowed, against
// t.z, or against the receiver's plane extended to the tap when
// receiver_plane is on (Isidoro 2006).
// units: t in map texture space; offset in uv (one texel is 1/size).
// cost: one shadow-sampler fetch (2×2 texels with linear_compare).
float shadow_tap(vec3 t, vec2 offset) {
  return texture(shadow_map, vec3(t.xy + offset, min(t.z + dot(receiver_gradient, offset), 1.0)));
}
// clamp(v, 0, 1) that lets NaN and Inf through to the harness's finiteness
// check. Written with isnan/isinf: NIR turns `v > 1.0 ? 1.0 : v` into
// fmin(v, 1.0), which maps NaN to 1.
// cost: a few ALU operations.
float clamp_unit(float v) { return (isnan(v) || isinf(v)) ? v : clamp(v, 0.0, 1.0); }
// The receiver's view depth: its distance along the light's axis.
// units: world units (compare with view_depth() of a map texel).
// cost: one matrix row product.
float receiver_view_depth() { return -(light_view * vec4(receiver_world, 1.0)).z; }
)glsl";

// Where a world point falls in the light's map, and the receiver's geometry
// there: light_coords(), offset_world(), receiver_plane_gradient(),
// above_horizon(). No #version: append it after one.
inline constexpr const char* kLightLookupGlsl = R"glsl(
// The point `world` in the map's texture space, its depth clamped to 1 so
// that receivers beyond the far plane compare as unshadowed when nothing is
// in front of them.
// units: world in world units; returns uv in [0,1]² inside the map, z a
// window depth.
// cost: one matrix-vector product and a divide.
vec3 light_coords(mat4 light_view_projection, vec3 world) {
  vec4 c = light_view_projection * vec4(world, 1.0);
  vec3 ndc = c.xyz / c.w;
  vec3 t = ndc * 0.5 + 0.5;
  t.z = min(t.z, 1.0);
  return t;
}
// The receiver moved along its geometric normal by normal_offset × its
// distance to the light point (normal-offset shadows, Holbert 2011).
// units: world units; normal_offset per unit distance.
vec3 offset_world(vec3 world, vec3 geometric_normal, vec3 light_point, float normal_offset) {
  return world + geometric_normal * (normal_offset * distance(world, light_point));
}
// light_coords() without the clamp of the depth to 1.
// units: as light_coords().
vec3 light_coords_unclamped(mat4 light_view_projection, vec3 world) {
  vec4 c = light_view_projection * vec4(world, 1.0);
  return (c.xyz / c.w) * 0.5 + 0.5;
}
// Steps along two tangents of the receiver's plane, projects them into the
// map and inverts the 2×2 Jacobian: how depth changes per unit of uv.
// units: window depth per uv; vec2(0) where the plane is seen edge-on.
// cost: three projections and a 2×2 inverse.
vec2 receiver_plane_gradient(mat4 light_view_projection, vec3 world, vec3 n) {
  vec3 a = normalize(cross(n, abs(n.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
  vec3 b = cross(n, a);
  float e = 1e-3 * max(length(world), 1.0);
  vec3 t0 = light_coords_unclamped(light_view_projection, world);
  vec3 ta = light_coords_unclamped(light_view_projection, world + e * a) - t0;
  vec3 tb = light_coords_unclamped(light_view_projection, world + e * b) - t0;
  mat2 j = mat2(ta.xy, tb.xy);
  float det = determinant(j);
  // Edge-on (the tangents project almost parallel): no usable plane.
  if (abs(det) < 0.02 * length(ta.xy) * length(tb.xy)) return vec2(0.0);
  return vec2(ta.z, tb.z) * inverse(j);
}
// 1 when the light point lies above the surface's tangent plane; below it the
// surface itself occludes the light (the reference counts it so too).
// units: 0 or 1.
float above_horizon(vec3 geometric_normal, vec3 world, vec3 light_point) {
  return dot(geometric_normal, light_point - world) > 0.0 ? 1.0 : 0.0;
}
)glsl";

// The map's depths as distances: the uniform light_depth_range and
// view_depth(), depth01(). No #version: append it after one (MapLookupPass
// sets light_depth_range when the program uses it).
inline constexpr const char* kLightDepthGlsl = R"glsl(
// The map's near and far planes (LightFrustum::near_plane, ::far_plane).
// units: world units along the light's axis.
uniform vec2 light_depth_range;
// The map is orthographic (LightFrustum::orthographic, the sun's): its window
// depth is linear in view depth. False unless the pass sets it.
uniform bool light_orthographic;
// A window depth of the map (a raw depth_map texel) as a view depth.
// units: window depth in [0,1] -> world units along the light's axis.
float view_depth(float window_depth) {
  float n = light_depth_range.x, f = light_depth_range.y;
  if (light_orthographic) return n + window_depth * (f - n);
  return n * f / (f - window_depth * (f - n));
}
// A view depth mapped linearly to [0,1] between the near and far planes
// (far and beyond: 1).
// units: world units -> [0,1].
float depth01(float view_z) {
  return clamp((view_z - light_depth_range.x) / (light_depth_range.y - light_depth_range.x), 0.0, 1.0);
}
)glsl";

}  // namespace sb::techniques
