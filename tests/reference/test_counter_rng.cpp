// core/counter_rng.h against SplitMix64's published outputs, and the float
// rule the techniques' and the reference's sample points are defined by.
#include <gtest/gtest.h>

#include <cstdint>

#include "core/counter_rng.h"
#include "reference/stratify.h"

namespace {

// The first five outputs of splitmix64.c seeded with 1234567 (Rosetta Code,
// "Pseudo-random numbers/Splitmix64") and with 0 (Vigna's reference code).
TEST(referenceCounterRng, SplitMix64MatchesItsPublishedOutputs) {
  const uint64_t from_1234567[] = {6457827717110365317ull, 3203168211198807973ull,
                                   9817491932198370423ull, 4593380528125082431ull,
                                   16408922859458223821ull};
  const uint64_t from_0[] = {0xe220a8397b1dcdafull, 0x6e789e6aa1b965f4ull, 0x06c45d188009454full,
                             0xf88bb8a8724c81ecull, 0x1b39896a51a8749bull};
  for (uint64_t i = 0; i < 5; ++i) {
    EXPECT_EQ(sb::core::splitmix64(1234567, i), from_1234567[i]) << "output " << i;
    EXPECT_EQ(sb::core::splitmix64(0, i), from_0[i]) << "output " << i;
  }
}

// Counter-based: output i needs no state, and the stream runs past 2^32.
TEST(referenceCounterRng, OutputIsAFunctionOfSeedAndIndexOnly) {
  static_assert(sb::core::splitmix64(1234567, 4) == 16408922859458223821ull);
  // Stepping the state by gamma (the sequential form) reaches the same word.
  uint64_t state = 99;
  for (int i = 0; i < 1000; ++i) state += sb::core::kSplitMix64Gamma;
  EXPECT_EQ(sb::core::splitmix64(99, 999), sb::core::splitmix64_mix(state));
  EXPECT_NE(sb::core::splitmix64(99, uint64_t(1) << 32), sb::core::splitmix64(99, 0));
}

TEST(referenceCounterRng, FloatsAreTheTop24BitsTimes2ToMinus24) {
  EXPECT_EQ(sb::core::unit_float(0), 0.0f);
  EXPECT_EQ(sb::core::unit_float(0x000000ffffffffffull), 0.0f);  // only the top 24 bits count
  EXPECT_EQ(sb::core::unit_float(0x0000010000000000ull), 0x1p-24f);
  EXPECT_EQ(sb::core::unit_float(0x8000000000000000ull), 0.5f);
  EXPECT_EQ(sb::core::unit_float(~0ull), 1.0f - 0x1p-24f);  // never 1
  // 6457827717110365317 >> 40 = 5873360 (0x599ed0).
  EXPECT_EQ(sb::core::uniform_float(1234567, 0), 5873360.0f / 16777216.0f);
}

// The reference's sampler draws from the same generator: sample i's u is
// uniform_float(key, i), v the next 24 bits of the same word.
TEST(referenceCounterRng, ReferenceSamplesComeFromTheSameGenerator) {
  const uint64_t key = sb::reference::detail::pixel_key(3, 777, 64);
  for (uint32_t i = 0; i < 64; ++i) {
    float u = -1.0f, v = -1.0f;
    sb::reference::detail::sample_uv(key, i, u, v);
    EXPECT_EQ(u, sb::core::uniform_float(key, i));
    EXPECT_EQ(v, float((sb::core::splitmix64(key, i) >> 8) & 0xffffffu) * 0x1p-24f);
  }
}

}  // namespace
