#pragma once
// The cascaded lookup's fragment shader, in pieces: its inputs and
// shadow_tap() on the cascades' array (so that the kit's kPcfGlsl, which
// calls shadow_tap(t, offset), filters a cascade unchanged), then the
// per-cascade lookups (hard, PCF, PCSS under the sun) and main(): the
// cascade selection by view depth and the blend band between cascades.
//
// Why not the kit's map lookup (common/map_lookup.h) and kPcssGlsl: both
// read one 2D map from a perspective light (sampler2D depth_map, the
// perspective view_depth(), PCSS's widths from similar triangles towards a
// light at a point). The cascades are layers of an array seen through
// orthographic boxes, where depth is linear in distance and the sun's
// penumbra grows as (d_receiver − d_blocker)·2·tan(α/2).
namespace sb::techniques::cascaded {

inline constexpr const char* kCascadeInputsGlsl = R"glsl(#version 450 core
in vec2 uv;
layout(binding = 0) uniform sampler2D position_tex;
layout(binding = 2) uniform sampler2D normal_tex;
// The cascades: comparisons (1 lit) and raw window depths, one layer each.
layout(binding = 4) uniform sampler2DArrayShadow cascade_shadow;
layout(binding = 5) uniform sampler2DArray cascade_depth;
uniform int cascade_count;
uniform mat4 cascade_vp[8];
// Per cascade: xy the box's size (world units), z and w its near and far
// depths along the light (world units; window depth is linear between them).
uniform vec4 cascade_box[8];
// Per cascade: the camera view depth where it ends, and its blend band's
// width before that end (0: a hard seam).
uniform float cascade_end[8];
uniform float cascade_band[8];
uniform mat4 camera_view;
uniform vec3 to_sun;
// 2·tan(α/2), α the sun's angular diameter: the penumbra's width per unit of
// distance between blocker and receiver along the light.
uniform float sun_spread;
uniform float normal_offset;  // in texels of the pixel's cascade
uniform int filter_mode;      // 0 hard, 1 pcf, 2 pcss
uniform int filter_radius;    // PCF grid half side
uniform int search_radius;    // PCSS blocker-search grid half side
uniform float min_filter_texels;
uniform bool show_cascades;
// Write the world size of the pixel's cascade's texel (its box's larger side / map size).
uniform bool show_texels;
out float visibility;

// The cascade shadow_tap() reads; set before each cascade's lookup.
int cascade = 0;
// kPcfGlsl's taps add receiver_gradient·offset to t.z: no receiver plane here.
vec2 receiver_gradient = vec2(0.0);
float shadow_tap(vec3 t, vec2 offset) {
  return texture(cascade_shadow, vec4(t.xy + offset, float(cascade), min(t.z, 1.0)));
}
)glsl";

inline constexpr const char* kCascadeLookupGlsl = R"glsl(
// A window depth of the current cascade as a distance along the light.
float light_depth(float window_depth) {
  vec4 b = cascade_box[cascade];
  return b.z + window_depth * (b.w - b.z);
}

// Mean light depth and count of blockers among (2·half_side+1)² taps over a
// rectangle of full widths width_uv around t (a square in the world: a box
// need not be square, so its uv widths differ).
vec2 sun_blocker_search(vec3 t, int half_side, vec2 width_uv) {
  vec2 step = 0.5 * width_uv / float(max(half_side, 1));
  float blockers = 0.0, depth_sum = 0.0;
  for (int y = -half_side; y <= half_side; ++y)
    for (int x = -half_side; x <= half_side; ++x) {
      float w = texture(cascade_depth, vec3(t.xy + vec2(x, y) * step, float(cascade))).r;
      if (w < t.z) {
        depth_sum += light_depth(w);
        blockers += 1.0;
      }
    }
  return vec2(blockers > 0.0 ? depth_sum / blockers : 0.0, blockers);
}

// The lit fraction of `world` (normal n) in cascade i, or -1 when the point
// falls outside the cascade's box.
float lit_in_cascade(int i, vec3 world, vec3 n) {
  cascade = i;
  vec2 texel_uv = 1.0 / vec2(textureSize(cascade_shadow, 0).xy);
  vec2 extent = cascade_box[i].xy;
  vec3 p = world + n * (normal_offset * max(extent.x, extent.y) * texel_uv.x);
  vec4 c = cascade_vp[i] * vec4(p, 1.0);
  vec3 t = c.xyz * 0.5 + 0.5;
  if (any(lessThan(t.xy, vec2(0.0))) || any(greaterThan(t.xy, vec2(1.0)))) return -1.0;
  t.z = min(t.z, 1.0);
  if (filter_mode == 0) return shadow_tap(t, vec2(0.0));
  if (filter_mode == 1) return pcf_grid(t, filter_radius, texel_uv);
  // PCSS under the sun: blockers can only lie between the receiver and the
  // box's near side, within the sun's cone from the receiver.
  float zr = light_depth(t.z);
  // World widths to uv per axis: a box need not be square (sdsm's are not).
  vec2 search_uv = sun_spread * (zr - cascade_box[i].z) / extent;
  vec2 blockers = sun_blocker_search(t, search_radius, max(search_uv, texel_uv));
  if (blockers.y == 0.0) return 1.0;
  vec2 penumbra_uv = sun_spread * max(zr - blockers.x, 0.0) / extent;
  vec2 radius_uv = max(0.5 * penumbra_uv, min_filter_texels * texel_uv);
  return pcf_grid(t, filter_radius, radius_uv / float(max(filter_radius, 1)));
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 pos = texelFetch(position_tex, px, 0);
  if (pos.w == 0.0) { visibility = 1.0; return; }
  vec3 n = texelFetch(normal_tex, px, 0).xyz;
  // Facing away from the sun, the surface itself hides it.
  float horizon = dot(n, to_sun) > 0.0 ? 1.0 : 0.0;
  float d = -(camera_view * vec4(pos.xyz, 1.0)).z;
  // The cascade selection: the first whose range reaches the pixel's depth.
  int i = 0;
  while (i < cascade_count - 1 && d > cascade_end[i]) ++i;
  float v = lit_in_cascade(i, pos.xyz, n);
  // The blend band: the last part of a cascade's range fades into the next.
  float w = 0.0;
  float band = cascade_band[i];
  if (i + 1 < cascade_count && band > 0.0 && d > cascade_end[i] - band) {
    w = clamp((d - (cascade_end[i] - band)) / band, 0.0, 1.0);
    float next = lit_in_cascade(i + 1, pos.xyz, n);
    if (next >= 0.0 && v >= 0.0) v = mix(v, next, w);
  }
  // Outside the box (only numerically, at its rim): nothing drawn there.
  if (v < 0.0) v = 1.0;
  if (show_texels) {
    visibility = max(cascade_box[i].x, cascade_box[i].y) / float(textureSize(cascade_shadow, 0).x);
    return;
  }
  if (show_cascades) {
    visibility = cascade_count > 1 ? (float(i) + w) / float(cascade_count - 1) : 0.0;
    return;
  }
  visibility = horizon * v;
}
)glsl";

}  // namespace sb::techniques::cascaded
