#pragma once
// Per-pixel rotation of a tap pattern, as GLSL a lit_fraction() may call:
// a different rotation in neighbouring pixels turns a small disk's banding
// into noise of the pattern's own scale. Pass kRotationNoiseGlsl with the
// lookup's kit GLSL (common/map_lookup.h), before the code that calls it.
//
// Interleaved gradient noise (Jimenez 2014, "Next generation post processing
// in Call of Duty: Advanced Warfare"): a closed form of the pixel's
// position, spread so that neighbouring pixels differ, with no texture to
// bind. The blue-noise option is a texture: common/blue_noise.h.
//
// What the kit guarantees here (shadowbench::shadow_kit, installed):
//   in     a pixel position (gl_FragCoord.xy);
//   out    noise in [0,1), up to float rounding of fract(); a rotation matrix;
//   GL     none: arithmetic only;
//   cost   no texture fetch; a few multiplies, and a cos and a sin.

namespace sb::techniques {

// Interleaved gradient noise and a rotation by a fraction of a turn.
// units: pixels in, [0,1) out; turns (1 = 2π radians).
// cost: no texture fetch.
inline constexpr const char* kRotationNoiseGlsl = R"glsl(
// Interleaved gradient noise (Jimenez 2014) at a pixel.
// fract(52.9829189 · fract(dot(pixel, (0.06711056, 0.00583715)))), a closed form, no table.
// Pass gl_FragCoord.xy (pixel centres, x + 0.5); the same pixel gives the same value every frame.
// units: pixel in window pixels; returns [0,1).
// cost: no texture fetch; a dot product, two fract().
float interleaved_gradient_noise(vec2 pixel) {
  return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

// The counter-clockwise 2×2 rotation by `turns` full turns, i.e. by 2π·turns radians.
// rotation_by_turns(interleaved_gradient_noise(gl_FragCoord.xy)) rotates a disk per pixel.
// units: turns (1 = 360°); multiplies offsets in any unit.
// cost: one cos, one sin.
mat2 rotation_by_turns(float turns) {
  float a = 6.28318531 * turns;
  return mat2(cos(a), sin(a), -sin(a), cos(a));
}
)glsl";

}  // namespace sb::techniques
