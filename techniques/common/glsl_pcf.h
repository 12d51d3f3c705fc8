#pragma once
// Percentage-closer filtering (Reeves et al. 1987) as GLSL functions a
// lit_fraction() may call: the mean of depth comparisons (shadow_tap, 1 lit,
// 0 shadowed) over a square grid of taps or over a disk of taps. Pass
// kPcfGlsl as the lookup's kit GLSL (MapLookupPass / SingleMapTechnique,
// common/map_lookup.h), so that it comes before the code that calls it and
// a compile error in your own GLSL names your own line:
//   SingleMapTechnique(p, "mine", kMyLitFraction, false, kPcfGlsl)
//
// A grid is given by its HALF SIDE h (side 2h+1, (2h+1)² taps); a disk by
// its tap COUNT and its unit-disk offsets (common/sample_disks.h). Kernel
// sizes are RADII: from the centre tap to the outermost one.
//
// What the kit guarantees here (shadowbench::shadow_kit, installed):
//   in     the map lookup's prelude (shadow_tap, receiver_gradient);
//   out    means of shadow_tap's values: in [0,1] when each tap is;
//   GL     none of its own: the calls read shadow_map (unit 1) only;
//   cost   one shadow_map fetch per tap (each a 2×2 bilinear comparison when
//          the pass compares linearly).

namespace sb::techniques {

// PCF over a grid and over a disk of taps; disk arrays hold MAX_DISK_TAPS (= kMaxDiskTaps).
// units: offsets and radii in map uv; results in [0,1] (fraction of taps lit).
// cost: one shadow_map fetch per tap.
inline constexpr const char* kPcfGlsl = R"glsl(
#ifndef MAX_DISK_TAPS
#define MAX_DISK_TAPS 64
#endif

// Mean of (2·half_side+1)² comparisons on a square grid centred on t, spacing_uv apart.
// The kernel's radius (centre to outermost tap) is half_side·spacing_uv.
// units: spacing_uv in map uv (1/textureSize for one texel); returns [0,1].
// cost: (2·half_side+1)² shadow_map fetches.
float pcf_grid(vec3 t, int half_side, vec2 spacing_uv) {
  float sum = 0.0;
  for (int y = -half_side; y <= half_side; ++y)
    for (int x = -half_side; x <= half_side; ++x) sum += shadow_tap(t, vec2(x, y) * spacing_uv);
  int side = 2 * half_side + 1;
  return sum / float(side * side);
}

// Mean of (2·half_side+1)² comparisons on a square grid of RADIUS radius_uv (width 2·radius_uv).
// The outermost taps lie radius_uv from t along each axis; half_side 0 is one tap at t.
// units: radius_uv in map uv; returns [0,1].
// cost: (2·half_side+1)² shadow_map fetches.
float pcf_grid_radius(vec3 t, int half_side, float radius_uv) {
  return pcf_grid(t, half_side, vec2(radius_uv / float(max(half_side, 1))));
}

// Sum (not mean) of the comparisons at taps first..end-1 of a disk, rotated, then scaled.
// Tap i lies at t + rotation · disk[i] · radius_uv; split a disk in two calls for an early-out.
// units: disk on the unit disk (common/sample_disks.h); radius_uv in map uv per axis.
// cost: end − first shadow_map fetches.
float pcf_disk_sum(vec3 t, vec2 disk[MAX_DISK_TAPS], int first, int end, mat2 rotation,
                   vec2 radius_uv) {
  float sum = 0.0;
  for (int i = first; i < end; ++i) sum += shadow_tap(t, rotation * disk[i] * radius_uv);
  return sum;
}

// Mean of the comparisons at the first `count` taps of a disk of RADIUS radius_uv, rotated.
// units: disk on the unit disk; radius_uv in map uv per axis; returns [0,1].
// cost: count shadow_map fetches.
float pcf_disk(vec3 t, vec2 disk[MAX_DISK_TAPS], int count, mat2 rotation, vec2 radius_uv) {
  return pcf_disk_sum(t, disk, 0, count, rotation, radius_uv) / float(count);
}
)glsl";

}  // namespace sb::techniques
