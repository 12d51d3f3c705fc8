#pragma once
// FLIP's filters (metrics/flip.h) as separable 1D taps for a viewing distance
// in pixels per degree: the contrast sensitivity of each opponent channel
// (spatial) and the derivatives of a Gaussian that find edges and points
// on the luminance (features).
#include <vector>

namespace sb::metrics::flip_detail {

// The feature filters' width in degrees, and the feature difference's
// exponent q_f.
inline constexpr float kFeatureWidth = 0.082f, kQf = 0.5f;

struct SpatialFilters {
  int radius = 0;
  std::vector<float> y, cx, cz1, cz2;  // 2 * radius + 1 taps each
};

// 1D filters whose outer products make the 2D ones: Y's and Cx's normalised
// to sum 1; Cz's two Gaussians each the square root of its 2D one (so that
// cz1(x) cz1(y) + cz2(x) cz2(y) is the sum of two 2D Gaussians), scaled
// together so that the 2D sum is 1.
SpatialFilters spatial_filters(double ppd);

struct FeatureFilters {
  int radius = 0;
  std::vector<float> g, dg, ddg;  // Gaussian, its first and second derivative
};

// sd = 0.5 * 0.082 degrees in pixels, radius 3 sd. The Gaussian sums to 1;
// each derivative's positive taps sum to 1 and its negative taps to -1.
FeatureFilters feature_filters(double ppd);

}  // namespace sb::metrics::flip_detail
