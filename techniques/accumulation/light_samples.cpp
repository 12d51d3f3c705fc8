#include "accumulation/light_samples.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "core/counter_rng.h"

namespace sb::techniques::accumulation {

using core::uniform_float;

namespace {

// The largest m <= sqrt(n) dividing n: an m × (n/m) grid of strata.
int grid_rows(int n) {
  int m = static_cast<int>(std::sqrt(static_cast<double>(n)));
  while (m > 1 && n % m != 0) --m;
  return m;
}

// Strata at most twice as wide as tall still stratify both directions.
constexpr int kMaxGridAspect = 2;

// i's binary digits mirrored about the point: 0.b0 b1 b2 ... in [0, 1).
double radical_inverse_base2(uint32_t i) {
  i = (i << 16) | (i >> 16);
  i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
  i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
  i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
  i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
  return double(i) * 0x1p-32;
}

// x mod 1 as a float strictly below 1 (rounding must not reach the far edge).
float wrap_unit(double x) {
  const float f = float(x - std::floor(x));
  return f < 1.0f ? f : std::nextafter(1.0f, 0.0f);
}

}  // namespace

std::vector<glm::vec2> light_samples(int n, bool jitter, unsigned seed) {
  if (n < 1) throw std::invalid_argument("light_samples: n must be at least 1");
  std::vector<glm::vec2> out;
  out.reserve(size_t(n));

  const int rows = grid_rows(n);
  const int cols = n / rows;
  if (cols <= kMaxGridAspect * rows) {
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        // Stratum k's jitter is draws 2k (s) and 2k + 1 (t) of the seed's stream.
        const uint64_t k = uint64_t(r) * uint64_t(cols) + uint64_t(c);
        const float s = (float(c) + (jitter ? uniform_float(seed, 2 * k) : 0.5f)) / float(cols);
        const float t = (float(r) + (jitter ? uniform_float(seed, 2 * k + 1) : 0.5f)) / float(rows);
        out.emplace_back(s, t);
      }
    return out;
  }

  // Radical inverses of i < n are multiples of 2^-k (2^k >= n): half a step
  // centres them, as (i+½)/n centres s.
  uint64_t dyadic = 1;
  while (dyadic < uint64_t(n)) dyadic *= 2;
  const double step = 1.0 / double(dyadic);
  double shift_s = 0.0, shift_t = 0.0;
  if (jitter) {
    shift_s = uniform_float(seed, 0);
    shift_t = uniform_float(seed, 1);
  }
  for (int i = 0; i < n; ++i) {
    const double s = (double(i) + 0.5) / double(n);
    const double t = radical_inverse_base2(uint32_t(i)) + 0.5 * step;
    out.emplace_back(wrap_unit(s + shift_s), wrap_unit(t + shift_t));
  }
  return out;
}

std::vector<float> segment_samples(int n, bool jitter, unsigned seed) {
  if (n < 1) throw std::invalid_argument("segment_samples: n must be at least 1");
  std::vector<float> out;
  out.reserve(size_t(n));
  for (int i = 0; i < n; ++i)
    out.push_back(wrap_unit(
        (double(i) + (jitter ? double(uniform_float(seed, uint64_t(i))) : 0.5)) / double(n)));
  return out;
}

LightSampleLayouts light_sample_layouts(int n, bool jitter, unsigned seed) {
  return {light_samples(n, jitter, seed), segment_samples(n, jitter, seed)};
}

}  // namespace sb::techniques::accumulation
