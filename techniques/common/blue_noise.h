#pragma once
// A blue-noise mask for per-pixel rotation (the texture option beside
// interleaved gradient noise, common/glsl_rotation_noise.h): a side×side
// tile whose values, thresholded at any level, leave points spread evenly
// with no low-frequency clumps. Made by void-and-cluster (Ulichney 1993) on
// the CPU from a seed (core/counter_rng.h), tiled toroidally so that
// repeats show no seam. The same seed gives the same tile on a given build;
// the energies use the C library's exp(), so another libm may break a
// near-tie the other way.
//
// What the kit guarantees here (shadowbench::shadow_kit, installed):
//   in     side (a power of two, 4..256), a seed;
//   out    side² values (k + ½)/side², each k in [0, side²) exactly once,
//          row-major, in (0, 1);
//   GL     make_blue_noise_texture(): an R32F texture, nearest, repeating;
//          the technique binds it on a unit of its own (4 and up) and reads
//          it with blue_noise() from kBlueNoiseGlsl;
//   cost   O(side⁴) on the CPU (64²: about 17 million multiply-adds), once,
//          in prepare(); one texelFetch per pixel on the GPU.
#include <vector>

#include "gl/objects.h"

namespace sb::techniques {

// A side×side void-and-cluster blue-noise mask, row-major, values (rank + ½)/side².
// Initial pattern: pixel i is set when core::uniform_float(seed, i) < 0.1; energy is a
// toroidal Gaussian of σ = 1.5 pixels.
// units: pixels in, (0,1) out.
// cost: O(side⁴) CPU operations.
std::vector<float> blue_noise_mask(int side, unsigned seed);

// blue_noise_mask(side, seed) as an R32F texture, nearest filtering, repeating.
// units: texels = pixels.
// cost: the mask's, then one upload.
gl::Texture make_blue_noise_texture(int side, unsigned seed);

// GLSL: blue_noise(mask, pixel) reads the tile at a window pixel, repeating.
// units: pixel in window pixels (gl_FragCoord.xy); returns (0,1).
// cost: one texelFetch.
inline constexpr const char* kBlueNoiseGlsl = R"glsl(
// The blue-noise mask's value at a window pixel, the tile repeated over the window.
// Declare the mask as `layout(binding = N) uniform sampler2D name;` on a unit of your own.
// units: pixel in window pixels (gl_FragCoord.xy); returns (0,1).
// cost: one texelFetch.
float blue_noise(sampler2D mask, vec2 pixel) {
  ivec2 side = textureSize(mask, 0);
  return texelFetch(mask, ivec2(floor(pixel)) % side, 0).r;
}
)glsl";

}  // namespace sb::techniques
