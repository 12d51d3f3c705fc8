#pragma once
// Stability figures of a visibility buffer (docs/stability.md): how much it
// flickers between consecutive frames of a slowly moving light, and how fast
// it changes with a continuous parameter. Pure image arithmetic: the frames
// are rendered by run/.
#include <cstdint>
#include <vector>

#include "core/image.h"

namespace sb::metrics {

// Per-pixel |V_k - V_(k-1)| over consecutive frames, pooled over every
// pair of frames and every masked pixel.
struct FlickerStats {
  int frames = 0;      // images compared (pairs: frames - 1)
  size_t samples = 0;  // pixels × pairs
  double mean = 0;     // mean |ΔV|
  double p99 = 0;      // its 99th percentile (numpy's default interpolation)
  double max = 0;      // its largest value
  // Share of the samples over 0.05: pixels that pop (a hard edge crossing
  // them) rather than drift with the light.
  double frac_over_005 = 0;
  size_t nonfinite = 0;  // pairs where either value is NaN or infinite (left out)
};

// Throws std::invalid_argument for fewer than two frames, frames of
// different shapes or more than one channel, or a mask of another size.
FlickerStats flicker(const std::vector<core::ImageF>& frames,
                     const std::vector<uint8_t>* mask = nullptr);

// Central finite difference of V in one parameter: V(p + h) and V(p - h).
struct Sensitivity {
  double step = 0;  // h
  // Mean over the masked pixels of |V+ - V-| / (2h): V per unit of p. The
  // mean absolute value, not the RMS: where an edge moves with p, the RMS
  // of the difference grows like √h and has no limit as h shrinks, while
  // the mean converges (to the edge's length × its jump × its speed).
  double dv_dp = 0;
  // dv_dp × |p|: the mean change of V per relative change of p (an
  // elasticity; 0 when p is 0, where only dv_dp has a meaning).
  double relative = 0;
};

// Throws std::invalid_argument when h <= 0, or on shapes as flicker().
Sensitivity sensitivity(const core::ImageF& v_plus, const core::ImageF& v_minus, double value,
                        double h, const std::vector<uint8_t>* mask = nullptr);

}  // namespace sb::metrics
