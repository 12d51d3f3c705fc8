#pragma once
// Tap patterns on the unit disk for PCF and blocker searches over a disk
// (GLSL: common/glsl_pcf.h, common/glsl_pcss.h): deterministic functions of
// (n, seed), the same points with any compiler and standard library, since
// their random numbers are core/counter_rng.h's. Both put the outermost taps
// first, so that an early-out over the first k taps tries the disk's rim.
// Scale them by the kernel's RADIUS (not its width) in uv or texels.
//
// What the kit guarantees here (shadowbench::shadow_kit, installed):
//   in     n, the number of taps (a COUNT, not a grid side), 1..kMaxDiskTaps
//          for the GLSL arrays; a seed;
//   out    n points with |p| <= 1;
//   GL     none: plain CPU code;
//   cost   jittered_disk O(n); poisson_disk O(n) distance tests per dart,
//          a few times n darts.
#include <glm/vec2.hpp>
#include <vector>

namespace sb::techniques {

// The size of the GLSL tap arrays (MAX_DISK_TAPS in common/glsl_pcf.h).
inline constexpr int kMaxDiskTaps = 64;

// n taps on a golden-angle (Vogel) spiral, each jittered inside its equal-area ring.
// Before the outermost-first reversal, point i (0-based) is
// (r_i cos phi_i, r_i sin phi_i) in float arithmetic, with
//   r_i = sqrt((i + u_i) / n),  phi_i = i * (pi * (3 - sqrt 5)),
//   u_i = core::uniform_float(seed, i).
// units: unit disk (multiply by the kernel's radius).
// cost: O(n).
std::vector<glm::vec2> jittered_disk(int n, unsigned seed);

// The distance poisson_disk(n, ·) keeps between any two taps: 2·sqrt(0.3 / n).
// That is n discs of radius spacing/2 covering 30% of the unit disk's area,
// well below random dart throwing's jamming limit (about 55%).
// units: unit disk.
// cost: one sqrt.
float poisson_disk_spacing(int n);

// n Poisson-disk taps: darts kept if poisson_disk_spacing(n) from every tap kept before.
// Dart k is uniform on the disk: radius sqrt(u_2k), angle 2π·u_2k+1, with
// u_j = core::uniform_float(seed, j). The taps are sorted outermost first.
// Should 1000·n darts not place all n taps (never for n <= kMaxDiskTaps and
// the seeds the tests try), the spacing shrinks by 10% and throwing goes on.
// units: unit disk (multiply by the kernel's radius).
// cost: O(n) distance tests per dart, a few times n darts.
std::vector<glm::vec2> poisson_disk(int n, unsigned seed);

}  // namespace sb::techniques
