#pragma once
// FLIP's (metrics/flip.h) log2, exp2, power and cube root as plain
// arithmetic on the float's bits, so that the per-pixel loops vectorise (the
// C library's calls do not): about 1e-7 relative error, far below the 1e-4
// the maps are held to. Always inlined, into each vector width's band
// (flip_tile.cpp).
#include <bit>
#include <cstdint>
#include <numbers>

namespace sb::metrics::flip_detail {

// log2(x) for a normal x > 0: the exponent, plus log2 of the mantissa m in
// [1, 2) by the series of 2 atanh(s) / ln 2, s = (m - 1) / (m + 1) < 1/3
// (the first term left out is below 1e-7).
[[gnu::always_inline]] inline float fast_log2(float x) {
  const auto bits = std::bit_cast<std::uint32_t>(x);
  const float e = static_cast<float>(static_cast<int>(bits >> 23) - 127);
  const float m = std::bit_cast<float>((bits & 0x007FFFFFu) | 0x3F800000u);
  const float z = (m - 1.0f) / (m + 1.0f), z2 = z * z;
  const float series =
      z * (1.0f + z2 * (1.0f / 3 + z2 * (1.0f / 5 + z2 * (1.0f / 7 + z2 * (1.0f / 9 + z2 / 11)))));
  return e + series * (2.0f / std::numbers::ln2_v<float>);
}

// 2^y for y in [-126, 126]: 2^n by the exponent bits, 2^f (|f| <= 1/2) by
// its Taylor series to the 7th power (error below 2e-7).
[[gnu::always_inline]] inline float fast_exp2(float y) {
  // Written so that a NaN becomes -126 (a NaN's conversion to int would be
  // undefined).
  y = y > -126.0f ? y : -126.0f;
  y = y < 126.0f ? y : 126.0f;
  const int n = static_cast<int>(y + 126.5f) - 126;  // round to nearest, as an int conversion
  const float t = (y - static_cast<float>(n)) * std::numbers::ln2_v<float>;
  const float series =
      1.0f +
      t * (1.0f +
           t * (1.0f / 2 +
                t * (1.0f / 6 + t * (1.0f / 24 + t * (1.0f / 120 + t * (1.0f / 720 + t / 5040))))));
  return series * std::bit_cast<float>(static_cast<std::uint32_t>(n + 127) << 23);
}

// x^p for x >= 0 (0 for x = 0, p > 0). Both sides of the choice are
// computed (on a safe argument) and one is picked, so that the loops stay
// free of branches and vectorise.
[[gnu::always_inline]] inline float fast_pow(float x, float p) {
  const float v = fast_exp2(p * fast_log2(x > 1e-30f ? x : 1e-30f));
  return x > 0.0f ? v : 0.0f;
}

// The cube root of t > 0: 2^(log2(t) / 3), then one Newton step.
[[gnu::always_inline]] inline float fast_cbrt(float t) {
  const float y = fast_exp2(fast_log2(t) * (1.0f / 3));
  return y - (y * y * y - t) / (3.0f * y * y);
}

}  // namespace sb::metrics::flip_detail
