#pragma once
// raytraced's compute shader, in pieces: the light samples (Owen-scrambled
// Sobol points, Burley 2020), the ray offset's point query (the reference's
// rule, reference/ray_offset.h), the any-hit traversal with alpha masks, and
// the main pass that writes V. The buffers' layout is gpu_casters.h's.
namespace sb::techniques::raytraced {

// Inputs, outputs and the casters' buffers.
inline constexpr const char* kRaytracedInputsGlsl = R"glsl(
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D position_tex;
layout(binding = 1) uniform sampler2D normal_tex;
layout(binding = 0, r32f) uniform writeonly image2D visibility;
layout(std430, binding = 0) readonly buffer Nodes { vec4 nodes[]; };
layout(std430, binding = 1) readonly buffer Triangles { vec4 tris[]; };
layout(std430, binding = 2) readonly buffer Masks { vec4 masks[]; };
layout(std430, binding = 3) readonly buffer Textures { uvec4 textures[]; };
layout(std430, binding = 4) readonly buffer Alphas { uint alphas[]; };

uniform ivec2 size;
uniform int spp;
uniform uint frame_seed;  // the seed parameter and the frame index, hashed
uniform bool has_casters;
uniform bool sun;
uniform vec3 light_center;
uniform vec3 corner, eu, ev;  // a local light: corner + s*eu + t*ev
uniform vec3 axis, e1, e2;    // the sun: axis + tan_radius*(x*e1 + y*e2), (x, y) on the disk
uniform float tan_radius;
// sequence "blue_noise": one scrambled point set per frame, shifted per pixel
// by two blue-noise masks (units 4 and 5).
uniform bool blue;
layout(binding = 4) uniform sampler2D blue_x;
layout(binding = 5) uniform sampler2D blue_y;
)glsl";

// Sample points: Burley 2020, "Practical Hash-based Owen Scrambling"
// (JCGT 9(4)), listings 1-4: the 2-D Sobol sequence (dimension 0 the van
// der Corput sequence, dimension 1 Sobol's second, direction numbers
// v_{k+1} = v_k ^ (v_k >> 1)), its index shuffled and each coordinate
// scrambled by the Laine-Karras hash, seeds per pixel and frame from
// Wellons's lowbias32 hash.
inline constexpr const char* kSobolGlsl = R"glsl(
uint hash32(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}
uint laine_karras_permutation(uint x, uint seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}
uint nested_uniform_scramble(uint x, uint seed) {
  return bitfieldReverse(laine_karras_permutation(bitfieldReverse(x), seed));
}
uint sobol_second(uint index) {
  uint x = 0u, v = 0x80000000u;
  for (; index != 0u; index >>= 1, v ^= v >> 1)
    if ((index & 1u) != 0u) x ^= v;
  return x;
}
// Point `index` of the pixel's scrambled sequence in [0,1)^2, 24 bits a
// coordinate (as the reference's draws).
vec2 owen_sobol(uint index, uint seed) {
  uint i = nested_uniform_scramble(index, seed);
  uint x = nested_uniform_scramble(bitfieldReverse(i), hash32(seed ^ 0xa511e9b3u));
  uint y = nested_uniform_scramble(sobol_second(i), hash32(seed ^ 0x63d83595u));
  return vec2(uvec2(x, y) >> 8) * (1.0 / 16777216.0);
}
)glsl";

// The ray offset of the reference (reference/ray_offset.h), in the same
// double precision: eps = 2^-16 max(max_i |p_i|, M), M the largest
// |coordinate| of the caster triangles p lies on, found by a point query
// over the hierarchy (boxes widened by a sixteenth of the radius, more than
// the float rounding of the box test) and decided by lies_on_scale().
inline constexpr const char* kRayOffsetGlsl = R"glsl(
const double kOffsetRelative = 1.0 / 65536.0;
double largest_coordinate(dvec3 v) { return max(max(abs(v.x), abs(v.y)), abs(v.z)); }
double lies_on_scale(dvec3 p, double radius, dvec3 a, dvec3 b, dvec3 c) {
  dvec3 lo = min(a, min(b, c)), hi = max(a, max(b, c));
  dvec3 outside = max(lo - p, max(p - hi, dvec3(0.0)));
  if (!(dot(outside, outside) <= radius * radius)) return 0.0;
  double size = max(largest_coordinate(a), max(largest_coordinate(b), largest_coordinate(c)));
  dvec3 n = cross(b - a, c - a);
  double area2 = sqrt(dot(n, n));
  if (!(area2 > 0.0)) return 0.0;
  return abs(dot(p - a, n)) <= kOffsetRelative * size * area2 ? size : 0.0;
}
float ray_offset(vec3 pf) {
  dvec3 p = dvec3(pf);
  double radius = kOffsetRelative * largest_coordinate(p);
  double largest = 0.0;
  if (has_casters) {
    float reach = float(radius) * 1.0625;
    uint n = uint(nodes.length()) / 2u;
    for (uint i = 0u; i < n;) {
      vec4 a = nodes[2u * i], b = nodes[2u * i + 1u];
      uint count = floatBitsToUint(b.w), ref = floatBitsToUint(a.w);
      if (any(greaterThan(a.xyz - pf, vec3(reach))) || any(greaterThan(pf - b.xyz, vec3(reach)))) {
        i = count == 0u ? ref : i + 1u;  // past the subtree
        continue;
      }
      for (uint k = ref; k < ref + count; ++k)  // no triangles for an inner node
        largest = max(largest, lies_on_scale(p, radius, dvec3(tris[3u * k].xyz),
                                             dvec3(tris[3u * k + 1u].xyz),
                                             dvec3(tris[3u * k + 2u].xyz)));
      ++i;  // into the subtree, or past the leaf
    }
  }
  return float(kOffsetRelative * max(largest_coordinate(p), largest));
}
)glsl";

// Any-hit traversal: the watertight test and the conservative slab test of
// shadow_bvh.cpp, alpha masks sampled as core::sample_alpha does (nearest,
// wrapping, the texel index floor(u·width) in double).
inline constexpr const char* kTraversalGlsl = R"glsl(
int wrap_texel(float t, int n) {
  double i = floor(double(t) * double(n));
  int r = int(i - double(n) * floor(i / double(n)));
  if (r < 0) r += n;
  if (r >= n) r -= n;
  return r;
}
bool opaque(uint k, vec3 w) {
  uint m = floatBitsToUint(tris[3u * k].w);
  if (m == 0xffffffffu) return true;
  vec4 m0 = masks[2u * m], m1 = masks[2u * m + 1u];
  vec2 uv = w.x * m0.xy + w.y * m0.zw + w.z * m1.xy;
  uvec4 tex = textures[floatBitsToUint(m1.z)];
  int width = int(tex.y), height = int(tex.z);
  if (width <= 0 || height <= 0) return true;
  uint at = tex.x + uint(wrap_texel(uv.y, height) * width + wrap_texel(uv.x, width));
  uint alpha = (alphas[at >> 2] >> (8u * (at & 3u))) & 0xffu;
  return !(float(alpha) / 255.0 < m1.w);
}

// The ray's frame for the watertight test (Woop, Benthin & Wald 2013): the
// axis of the direction's largest component becomes z (cyclic, so the
// handedness stays), then a shear makes the ray the +z axis.
struct Shear {
  int kz;
  vec3 s;  // sx, sy, sz
};
vec3 permute(vec3 v, int kz) { return kz == 0 ? v.yzx : (kz == 1 ? v.zxy : v); }
Shear make_shear(vec3 d) {
  vec3 a = abs(d);
  int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  vec3 p = permute(d, kz);
  return Shear(kz, vec3(-p.x / p.z, -p.y / p.z, 1.0 / p.z));
}
// Each corner transformed alone and the edge functions unfused (`precise`),
// so that two triangles sharing an edge compute it alike, with opposite signs.
float ray_triangle(vec3 o, Shear sh, uint k, out vec3 w) {
  precise vec3 p0 = permute(tris[3u * k].xyz - o, sh.kz);
  precise vec3 p1 = permute(tris[3u * k + 1u].xyz - o, sh.kz);
  precise vec3 p2 = permute(tris[3u * k + 2u].xyz - o, sh.kz);
  p0.xy += sh.s.xy * p0.z;
  p1.xy += sh.s.xy * p1.z;
  p2.xy += sh.s.xy * p2.z;
  precise float e0 = p1.x * p2.y - p1.y * p2.x;
  precise float e1 = p2.x * p0.y - p2.y * p0.x;
  precise float e2 = p0.x * p1.y - p0.y * p1.x;
  if (e0 == 0.0 || e1 == 0.0 || e2 == 0.0) {
    e0 = float(double(p1.x) * double(p2.y) - double(p1.y) * double(p2.x));
    e1 = float(double(p2.x) * double(p0.y) - double(p2.y) * double(p0.x));
    e2 = float(double(p0.x) * double(p1.y) - double(p0.y) * double(p1.x));
  }
  w = vec3(0.0);
  if ((e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0)) return -1.0;
  float det = e0 + e1 + e2;
  if (det == 0.0) return -1.0;
  float t_scaled = e0 * (p0.z * sh.s.z) + e1 * (p1.z * sh.s.z) + e2 * (p2.z * sh.s.z);
  float inv = 1.0 / det;
  w = vec3(e0, e1, e2) * inv;
  return t_scaled * inv;
}
bool ray_box(vec3 o, vec3 inv, vec3 lo, vec3 hi, float tfar) {
  vec3 t0 = (lo - o) * inv, t1 = (hi - o) * inv;
  vec3 tmin = min(t0, t1), tmax = max(t0, t1);
  float enter = max(max(tmin.x, tmin.y), max(tmin.z, 0.0));
  float leave = min(min(tmax.x, tmax.y), min(tmax.z, tfar)) * 1.0000004;
  return enter <= leave;
}
vec3 safe_inverse(vec3 d) {
  vec3 tiny = vec3(1e-30);
  return 1.0 / mix(d, mix(tiny, -tiny, lessThan(d, vec3(0.0))), lessThan(abs(d), tiny));
}
bool occluded(vec3 o, vec3 d, float tfar) {
  vec3 inv = safe_inverse(d);
  Shear sh = make_shear(d);
  uint n = uint(nodes.length()) / 2u;
  for (uint i = 0u; i < n;) {
    vec4 a = nodes[2u * i], b = nodes[2u * i + 1u];
    uint count = floatBitsToUint(b.w), ref = floatBitsToUint(a.w);
    if (!ray_box(o, inv, a.xyz, b.xyz, tfar)) {
      i = count == 0u ? ref : i + 1u;  // past the subtree
      continue;
    }
    for (uint k = ref; k < ref + count; ++k) {  // no triangles for an inner node
      vec3 w;
      float t = ray_triangle(o, sh, k, w);
      if (t > 0.0 && t <= tfar && opaque(k, w)) return true;
    }
    ++i;  // into the subtree, or past the leaf
  }
  return false;
}
)glsl";

// The pass (after kBlueNoiseGlsl): per covered pixel, `spp` rays from the offset point to the
// light's samples, parametrised as the reference's (reference/pixel_rays.cpp):
// a local light's (s, t) on corner + s·eu + t·ev, rays ending 1e-4 short of
// it; the sun's through Shirley and Chiu's concentric map onto the disk on
// the plane at unit distance along its axis, rays to infinity. Samples
// below the tangent plane of the geometric normal never reach.
inline constexpr const char* kRaytracedMainGlsl = R"glsl(
vec2 concentric_disk(float s, float t) {
  float a = 2.0 * s - 1.0, b = 2.0 * t - 1.0;
  if (a == 0.0 && b == 0.0) return vec2(0.0);
  const float kQuarterPi = 0.785398163397448;
  float r, phi;
  if (abs(a) > abs(b)) {
    r = a;
    phi = kQuarterPi * (b / a);
  } else {
    r = b;
    phi = 2.0 * kQuarterPi - kQuarterPi * (a / b);
  }
  return vec2(r * cos(phi), r * sin(phi));
}
void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(px, size))) return;
  vec4 p = texelFetch(position_tex, px, 0);
  if (!(p.w > 0.5)) {
    imageStore(visibility, px, vec4(1.0));
    return;
  }
  vec3 n = texelFetch(normal_tex, px, 0).xyz;
  float len = length(n);
  if (len > 0.0) {
    n /= len;
  } else {  // no usable normal: towards the light, as the reference
    vec3 to_light = sun ? axis : light_center - p.xyz;
    float d = length(to_light);
    n = d > 0.0 ? to_light / d : vec3(0.0, 1.0, 0.0);
  }
  precise vec3 origin = p.xyz + ray_offset(p.xyz) * n;
  precise vec3 base = corner - origin;
  uint seed = hash32(uint(px.y * size.x + px.x) ^ frame_seed);
  vec2 shift = vec2(0.0);
  if (blue) {
    seed = hash32(frame_seed);
    shift = vec2(blue_noise(blue_x, vec2(px)), blue_noise(blue_y, vec2(px)));
  }
  float infinity = uintBitsToFloat(0x7f800000u);
  int reached = 0;
  for (int i = 0; i < spp; ++i) {
    vec2 st = fract(owen_sobol(uint(i), seed) + shift);
    vec3 d;
    float tfar;
    if (sun) {
      vec2 q = tan_radius * concentric_disk(st.x, st.y);
      d = axis + q.x * e1 + q.y * e2;
      tfar = infinity;
    } else {
      d = base + st.x * eu + st.y * ev;
      tfar = 1.0 - 1e-4;
    }
    if (dot(n, d) > 0.0 && !(has_casters && occluded(origin, d, tfar))) ++reached;
  }
  imageStore(visibility, px, vec4(float(reached) / float(spp)));
}
)glsl";

}  // namespace sb::techniques::raytraced
