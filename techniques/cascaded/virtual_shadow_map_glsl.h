#pragma once
// virtual_shadow_map's GLSL: the clipmap's uniforms and the per-pixel level
// choice, shared by the marking pass (compute) and the lookup (fragment),
// so that a pixel looks up exactly the pages it marked; then the two
// programs' own parts.
namespace sb::techniques::cascaded {

inline constexpr const char* kVirtualClipmapGlsl = R"glsl(
#define MAX_LEVELS 24
uniform mat4 light_view;  // the sun's frame (light_rotation)
uniform float near_depth;
uniform float far_depth;
uniform int level_count;
// Per level: xy its low corner in the sun's frame, z its texel (world units).
uniform vec3 level_lo_texel[MAX_LEVELS];
uniform int virtual_size;    // texels per level side
uniform int page_size;       // texels per page side
uniform int pages_per_side;  // virtual_size / page_size
uniform vec3 eye;
uniform float pixel_angle;  // 2·tan(fov_y / 2) / height: a pixel's footprint per unit distance
uniform int margin;         // texels the lookup reads around the pixel's own (filter, normal offset)

// Texel coordinates (x, y) in level l and window depth (z) of a point of the sun's frame.
vec3 level_coords(int l, vec3 q) {
  vec3 lt = level_lo_texel[l];
  return vec3((q.xy - lt.xy) / lt.z, (-q.z - near_depth) / (far_depth - near_depth));
}

// The pixel's level: the coarsest whose texel is no larger than the pixel's
// footprint (resolution matched), or a coarser one if that level's square
// does not hold the pixel and what its lookup reads around it.
int pixel_level(vec3 world, vec3 q) {
  float footprint = distance(world, eye) * pixel_angle;
  int l = int(clamp(floor(log2(footprint / level_lo_texel[0].z)), 0.0, float(level_count - 1)));
  for (; l < level_count - 1; ++l) {
    vec2 t = level_coords(l, q).xy;
    if (all(greaterThanEqual(t, vec2(margin))) && all(lessThan(t, vec2(virtual_size - margin))))
      break;
  }
  return l;
}
)glsl";

// Page marking: each covered pixel marks the pages its lookup will read,
// in its level and in the coarsest (the fallback), with its distance to
// the camera (atomicMin: a page keeps its nearest pixel's).
inline constexpr const char* kVirtualMarkGlsl = R"glsl(
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D position_tex;
layout(std430, binding = 0) buffer Marks { uint marks[]; };
uniform ivec2 image_size;

void mark(int l, vec2 t, uint d) {
  ivec2 a = clamp(ivec2(floor((t - float(margin)) / float(page_size))), ivec2(0),
                  ivec2(pages_per_side - 1));
  ivec2 b = clamp(ivec2(floor((t + float(margin)) / float(page_size))), ivec2(0),
                  ivec2(pages_per_side - 1));
  for (int y = a.y; y <= b.y; ++y)
    for (int x = a.x; x <= b.x; ++x)
      atomicMin(marks[(l * pages_per_side + y) * pages_per_side + x], d);
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(px, image_size))) return;
  vec4 pos = texelFetch(position_tex, px, 0);
  if (pos.w == 0.0) return;
  vec3 q = (light_view * vec4(pos.xyz, 1.0)).xyz;
  int l = pixel_level(pos.xyz, q);
  uint d = floatBitsToUint(distance(pos.xyz, eye));
  mark(l, level_coords(l, q).xy, d);
  if (l != level_count - 1) mark(level_count - 1, level_coords(level_count - 1, q).xy, d);
}
)glsl";

// The lookup: virtual texel → page table → physical texel in the pool.
// Every texel a filter reads goes through the page table on its own, so a
// PCF kernel crosses page borders as if the map were whole (no border
// texels in the pool). shadow_tap() is the kit's kPcfGlsl's tap.
inline constexpr const char* kVirtualLookupInputsGlsl = R"glsl(
in vec2 uv;
layout(binding = 0) uniform sampler2D position_tex;
layout(binding = 2) uniform sampler2D normal_tex;
layout(binding = 4) uniform sampler2D pool;              // raw window depths
layout(binding = 5) uniform isampler2DArray page_table;  // slot, -1 unmarked, -2 dropped
uniform int pool_pages_side;
uniform vec3 to_sun;
uniform float normal_offset;  // texels of the pixel's level
uniform int filter_mode;      // 0 hard, 1 pcf
uniform int filter_radius;    // PCF grid half side
uniform int output_mode;      // 0 V, 1 level, 2 slot, 3 fallback, 4 page table
out float visibility;

int current_level = 0;
bool missing = false;  // a texel read had no page in the pool

int page_slot(int l, ivec2 page) { return texelFetch(page_table, ivec3(page, l), 0).r; }

float texel_lit(ivec2 k, float z) {
  k = clamp(k, ivec2(0), ivec2(virtual_size - 1));
  ivec2 page = k / page_size;
  int slot = page_slot(current_level, page);
  if (slot < 0) {
    missing = true;
    return 1.0;
  }
  ivec2 origin = ivec2(slot % pool_pages_side, slot / pool_pages_side) * page_size;
  return z <= texelFetch(pool, origin + k - page * page_size, 0).r ? 1.0 : 0.0;
}

vec2 receiver_gradient = vec2(0.0);
// A bilinear comparison (as a hardware 2×2) at t.xy + offset, in level uv.
float shadow_tap(vec3 t, vec2 offset) {
  vec2 x = (t.xy + offset) * float(virtual_size) - 0.5;
  ivec2 k = ivec2(floor(x));
  vec2 f = fract(x);
  float a = mix(texel_lit(k, t.z), texel_lit(k + ivec2(1, 0), t.z), f.x);
  float b = mix(texel_lit(k + ivec2(0, 1), t.z), texel_lit(k + ivec2(1, 1), t.z), f.x);
  return mix(a, b, f.y);
}
)glsl";

inline constexpr const char* kVirtualLookupGlsl = R"glsl(
// The lit fraction in level l, or -1 when a texel it read had no page.
float lit_in_level(int l, vec3 world, vec3 n) {
  current_level = l;
  missing = false;
  vec3 p = world + n * (normal_offset * level_lo_texel[l].z);
  vec3 t = level_coords(l, (light_view * vec4(p, 1.0)).xyz);
  t.z = min(t.z, 1.0);
  float v = filter_mode == 0
                ? texel_lit(ivec2(floor(t.xy)), t.z)
                : pcf_grid(vec3(t.xy / float(virtual_size), t.z), filter_radius,
                           vec2(1.0 / float(virtual_size)));
  return missing ? -1.0 : v;
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  if (output_mode == 4) {
    // The page table laid out row-major over the image: 1 allocated, 0.5 dropped, 0 unmarked.
    int i = px.y * textureSize(position_tex, 0).x + px.x;
    int per_level = pages_per_side * pages_per_side;
    visibility = 0.0;
    if (i < per_level * level_count) {
      int s = page_slot(i / per_level, ivec2(i % pages_per_side, (i % per_level) / pages_per_side));
      visibility = s >= 0 ? 1.0 : s == -2 ? 0.5 : 0.0;
    }
    return;
  }
  vec4 pos = texelFetch(position_tex, px, 0);
  if (pos.w == 0.0) { visibility = output_mode == 0 ? 1.0 : 0.0; return; }
  vec3 n = texelFetch(normal_tex, px, 0).xyz;
  float horizon = dot(n, to_sun) > 0.0 ? 1.0 : 0.0;
  vec3 q = (light_view * vec4(pos.xyz, 1.0)).xyz;
  int l = pixel_level(pos.xyz, q);
  int fallback = 0;
  float v = lit_in_level(l, pos.xyz, n);
  if (v < 0.0 && l != level_count - 1) {
    fallback = 1;
    v = lit_in_level(level_count - 1, pos.xyz, n);
  }
  if (v < 0.0) {
    fallback = 2;
    v = 1.0;
  }
  if (output_mode == 1) visibility = level_count > 1 ? float(l) / float(level_count - 1) : 0.0;
  else if (output_mode == 2) {
    ivec2 page = ivec2(floor(level_coords(l, q).xy)) / page_size;
    int s = page_slot(l, clamp(page, ivec2(0), ivec2(pages_per_side - 1)));
    int pool_pages = pool_pages_side * pool_pages_side;
    visibility = s >= 0 ? float(s + 1) / float(pool_pages) : 0.0;
  } else if (output_mode == 3) visibility = 0.5 * float(fallback);
  else visibility = horizon * v;
}
)glsl";

}  // namespace sb::techniques::cascaded
