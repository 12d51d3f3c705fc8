#pragma once
// Where accumulation puts its N light points: (s, t) in [0,1)² on the area
// light (AreaLight::point), spread evenly in both directions for every N.
//
//   N = m·n, m the largest divisor <= √N, n <= 2m: the m×n grid of strata
//     (rows of n), one point per stratum, at its centre or (jitter) uniform
//     inside it. Square N gives the usual n×n jittered grid.
//   any other N (primes, 2·prime, ...): the m×n grid would be a few thin
//     columns (1×N for a prime), stratified in s only. They get the
//     Hammersley set ((i+½)/N, radical inverse of i in base 2, centred in
//     its dyadic interval), whose star discrepancy is O(log N / N) for any N;
//     jitter adds one seeded toroidal shift to all points (Cranley–Patterson
//     rotation), which keeps that structure and makes every point uniform.
//
// The jitter's uniforms are draws of core/counter_rng.h's generator,
// uniform_float(seed, j) (SplitMix64's output j, top 24 bits * 2^-24): on
// the grid, stratum k = row * n + column takes j = 2k for s and 2k + 1 for
// t; the Hammersley shift takes j = 0 (s) and 1 (t); a segment's stratum i
// takes j = i. The same (n, jitter, seed) gives the same bits with any
// standard library.
#include <glm/vec2.hpp>
#include <vector>

namespace sb::techniques::accumulation {

// N >= 1 points; the same (n, jitter, seed) always gives the same points.
std::vector<glm::vec2> light_samples(int n, bool jitter, unsigned seed);

// On a linear light (a segment) the square's t collapses: an m×n grid would
// put only n distinct strata along it, each point m times. A segment gets
// N strata of its own instead, s = (i + ½)/N or jittered inside each
// (AreaLight::segment_end). Same determinism as above.
std::vector<float> segment_samples(int n, bool jitter, unsigned seed);

// Both layouts of the same N, so that a technique can place its points on
// whichever light a frame has (the light is not known in prepare()).
struct LightSampleLayouts {
  std::vector<glm::vec2> square;  // AreaLight::point(s, t)
  std::vector<float> line;        // AreaLight::segment_end(s)
  size_t size() const { return square.size(); }
};
LightSampleLayouts light_sample_layouts(int n, bool jitter, unsigned seed);

}  // namespace sb::techniques::accumulation
