#pragma once
// pcf_jitter's taps: N points on the unit disk, a golden-angle (Vogel)
// spiral with each radius jittered inside its equal-area ring, ordered
// outermost first (the early-out taps).
//
// Before that reversal, point i (0-based) is (r_i cos phi_i, r_i sin phi_i),
// in float arithmetic,
//   r_i = sqrt((i + u_i) / N),  phi_i = i * (pi * (3 - sqrt 5)),
//   u_i = uniform_float(seed, i)   (core/counter_rng.h: SplitMix64's
//                                   output i, top 24 bits * 2^-24),
// so the same (N, seed) gives the same taps with any standard library.
#include <glm/vec2.hpp>
#include <vector>

namespace sb::techniques::shadow_map {

std::vector<glm::vec2> jittered_disk(int n, unsigned seed);

}  // namespace sb::techniques::shadow_map
