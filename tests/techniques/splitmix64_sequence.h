#pragma once
// SplitMix64 as splitmix64.c writes it (a state stepped by the golden gamma,
// then mixed), with the documented float rule: the tests' own copy of the
// generator, independent of core/counter_rng.h's indexed form. Its outputs
// are checked against the published ones in tests/reference/test_counter_rng.cpp.
#include <cstdint>
#include <vector>

namespace sbtest {

// The first `count` uniforms of stream `seed`: top 24 bits of each output,
// times 2^-24.
inline std::vector<float> splitmix64_uniforms(uint64_t seed, int count) {
  std::vector<float> out;
  uint64_t x = seed;
  for (int i = 0; i < count; ++i) {
    uint64_t z = (x += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z = z ^ (z >> 31);
    out.push_back(float(z >> 40) / 16777216.0f);
  }
  return out;
}

}  // namespace sbtest
