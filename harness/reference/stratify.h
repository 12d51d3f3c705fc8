#pragma once
// Light-sample layout and random numbers of the reference (internal, but
// exposed so the tests can check the stratification itself).
//
// N samples stratify the unit square (s,t) of the light into N equal-area
// cells: k = round(sqrt(N)) rows (at least 2 cells each), row r holding
// c_r = floor((r+1)N/k) - floor(rN/k) cells of width 1/c_r and height c_r/N
// (N = 1: one cell, the whole light).
// For N = n*n this is exactly the n×n jittered grid; for other N the cells are
// near-square (c_r differs by at most one between rows), so every N
// stratifies in both directions. One uniform sample per cell.
//
// A linear light (a segment) has one axis: square cells would collapse into
// ~sqrt(N) strata along it, so its layout is one row of N cells of width 1/N
// along that axis, spanning the other (Strata::AlongS or AlongT).
#include <cstdint>
#include <vector>

#include "core/counter_rng.h"

namespace sb::reference::detail {

struct Stratum {
  float s0, ds;   // s = s0 + u*ds
  float t0, dt;   // t = t0 + v*dt
  uint32_t cell;  // row-major cell index (rows contiguous)
};

// Which way the cells divide the unit square: both ways (a rectangle, and a
// point, whose samples all coincide), or only along s or only along t (a
// segment light along half_u or half_v).
enum class Strata : uint8_t { Square, AlongS, AlongT };

struct Layout {
  int spp = 0;
  int rows = 0;                // 1 for a segment's layout
  std::vector<int> row_start;  // first cell of each row, plus spp at the end
  // Trace order: 4×4 blocks of neighbouring cells, so one 16-ray packet sees
  // one compact patch of the light (coherent traversal); along a segment, the
  // cells in order.
  std::vector<Stratum> order;
  // Collapsed strata for the variance estimate: horizontal neighbour pairs in
  // each row (along a segment, neighbours along it), the last group a triple
  // when the row is odd. [begin, end).
  std::vector<uint32_t> group_begin;  // plus spp at the end
};

Layout make_layout(int spp, Strata strata = Strata::Square);

// SplitMix64's finaliser (core/counter_rng.h): a bijective 64-bit mixer.
inline uint64_t mix64(uint64_t z) { return core::splitmix64_mix(z); }

// Each pixel draws from its own stream keyed by (seed, pixel, spp), so the
// result does not depend on how pixels are spread over threads.
inline uint64_t pixel_key(uint64_t seed, uint64_t pixel, uint64_t spp) {
  return mix64(mix64(mix64(seed ^ 0x5b3e1f0a2c4d6e87ull) ^ pixel) ^ (spp * core::kSplitMix64Gamma));
}

// Counter-based draw: sample i gets two 24-bit uniforms in [0,1) from one
// output, splitmix64(key, i): u its top 24 bits (unit_float), v bits 8-31.
// No std distribution, so the same bits with any standard library.
inline void sample_uv(uint64_t key, uint32_t i, float& u, float& v) {
  const uint64_t z = core::splitmix64(key, i);
  u = core::unit_float(z);
  v = float(uint32_t(z >> 8) & 0xffffffu) * 0x1p-24f;
}

// Variance of the stratified estimator from the collapsed-strata estimate:
// (1/N^2) * sum over groups g of |g|/(|g|-1) * sum_{i in g} (f_i - mean_g)^2,
// with f_i = 1 for a visible sample. `visible` is indexed by cell. For N = 1
// (no pair) it is 1/4, the largest variance of one 0/1 sample.
double stratified_variance(const uint8_t* visible, const Layout& layout);

// The standard error σ of an estimate from one sample per cell: 0 when the
// samples all agree (then there is no spread to estimate: the pixel carries
// a stop bound instead, below). Else the square root of the mean of two
// collapsed-strata variances, one over the layout's own groups and one over
// pairs shifted by one cell along each row: each is conservative in
// expectation (reference.h), so their mean is, and it is 0 only where every
// row is all lit or all occluded. There the same mean over pairs down the
// columns of a square grid stands in, and where that is 0 too (only rows of
// unequal length), the unstratified binomial sqrt(p(1-p)/N). So no estimate
// strictly between 0 and 1 reports σ = 0. On a segment light's single row,
// an edge between two strata makes exactly one of the two groupings
// disagree: σ = 1/(√2 N) for every soft pixel, where the layout's own
// groups alone gave 1/N or 0.
double standard_error(const uint8_t* visible, const Layout& layout);

// n stratified samples all agree with probability at most (1 - p)^n when a
// fraction p of the light is hidden (or, alike, seen), and the agreeing
// estimate is then wrong by p. Whatever the pixel's V, the most such an
// estimate can be off on average is max_p p (1 - p)^n (stop_bias_bound),
// and its root mean square error at most max_p p (1 - p)^(n/2)
// (stop_rms_bound): the stop bound a pixel whose samples all agreed, with no
// proof that they could not disagree, reports beside its σ of 0. n >= 1.
double stop_bias_bound(int n);
double stop_rms_bound(int n);

}  // namespace sb::reference::detail
