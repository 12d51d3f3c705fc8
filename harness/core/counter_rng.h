#pragma once
// The project's random numbers: a counter-based generator whose every output
// is a fixed function of (seed, index), the same bits with any compiler and
// standard library. (The standard leaves the algorithms of
// std::uniform_real_distribution and the other std distributions to the
// library, so another library may turn the same engine bits into other
// numbers.)
//
// SplitMix64 (Steele, Lea & Flood 2014; Vigna's splitmix64.c): output i
// (0-based) of the generator seeded with `seed` is
//   mix(seed + (i + 1) * 0x9e3779b97f4a7c15)   (mod 2^64),
// with mix() the bijective finaliser below. Indexing it directly gives any
// sample without drawing the ones before it.
//
// Floats: the top 24 bits times 2^-24, i.e. k / 2^24 for k in [0, 2^24):
// exact in a float, uniform on that grid, never 1.
#include <cstdint>

namespace sb::core {

inline constexpr uint64_t kSplitMix64Gamma = 0x9e3779b97f4a7c15ull;

// SplitMix64's finaliser (Stafford's Mix13): a bijection of 64-bit words.
constexpr uint64_t splitmix64_mix(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Output `index` of SplitMix64 seeded with `seed`.
constexpr uint64_t splitmix64(uint64_t seed, uint64_t index) {
  return splitmix64_mix(seed + (index + 1) * kSplitMix64Gamma);
}

// A 64-bit word's top 24 bits as a float in [0, 1): k * 2^-24.
constexpr float unit_float(uint64_t bits) { return float(uint32_t(bits >> 40)) * 0x1p-24f; }

// Uniform draw `index` of stream `seed`: unit_float(splitmix64(seed, index)).
constexpr float uniform_float(uint64_t seed, uint64_t index) {
  return unit_float(splitmix64(seed, index));
}

}  // namespace sb::core
