#pragma once
// LDR-FLIP (Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström and
// Fairchild 2020, "FLIP: A Difference Evaluator for Alternating Images"):
// the difference an observer sees when flipping between a reference and a
// test image, per pixel in [0, 1], at a viewing distance given as pixels
// per degree of visual angle.
//
// As the paper, in the separable form of NVlabs' reference implementation
// (its misc/separatedConvolutions.pdf), which is what its published values
// come from:
//  - colour: linear RGB to YCxCz (opponent space, D65); each channel low-pass
//    filtered by the contrast sensitivity of its channel (a Gaussian for Y
//    and Cx, a sum of two for Cz; edges clamped), back to linear RGB, clamped
//    to [0, 1], to CIELAB with the Hunt adjustment (a*, b* scaled by
//    0.01 L*), HyAB distance, raised to q_c = 0.7 and remapped so that p_c =
//    0.4 of the largest distance (green to blue) maps to p_t = 0.95;
//  - features: on the luminance, edges (first derivative of a Gaussian of
//    sd 0.5 * 0.082 degrees) and points (second derivative); the larger of
//    the two magnitude differences over sqrt(2), raised to q_f = 0.5;
//  - FLIP = colour difference ^ (1 - feature difference).
// The mean is the plain mean of the map (the paper's pooled value).
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "metrics/simd_path.h"

namespace sb::metrics {

// The paper's default: a 0.7 m wide monitor of 3840 pixels seen from 0.7 m
// (3840 * pi / 180 pixels per degree).
inline constexpr double kFlipDefaultPixelsPerDegree = 67.02064327658226;

struct FlipResult {
  core::ImageF error;  // one channel, in [0, 1]
  double mean = 0;
};

// What flip() computes of a reference image alone: its colour filtered and
// in Hunt L*a*b*, its edge and point magnitudes (five floats a pixel).
// Made once for the many test images measured against one reference, it
// halves their filtering, and flip() against it gives the same bits as
// against the image. Throws as flip() does for a bad image or viewing
// distance.
class FlipReference {
 public:
  explicit FlipReference(const core::ImageF& reference,
                         double pixels_per_degree = kFlipDefaultPixelsPerDegree,
                         detail::SimdPath path = detail::widest_simd_path());
  int width() const { return width_; }
  int height() const { return height_; }
  double pixels_per_degree() const { return pixels_per_degree_; }
  const std::vector<float>& planes() const { return planes_; }

 private:
  int width_, height_;
  double pixels_per_degree_;
  std::vector<float> planes_;
};

// FLIP of `test` against `reference`, both linear RGB (3 or 4 channels; a
// 4th is ignored) or grey (1 channel, as R = G = B), the same size; values
// are clamped to [0, 1] first, as the paper's LDR input is, and NaN is read
// as 0. Throws
// std::invalid_argument for different sizes, other channel counts, an empty
// image, or pixels_per_degree not in (0, 1000].
FlipResult flip(const core::ImageF& reference, const core::ImageF& test,
                double pixels_per_degree = kFlipDefaultPixelsPerDegree);

// flip(image, test) for the FlipReference of `image`, the same bits; throws
// also for a test image of another size.
FlipResult flip(const FlipReference& reference, const core::ImageF& test);

// The distance in pixels (along x and along y) beyond which a pixel's
// values change no FLIP value: the wider of the colour and feature filters'
// radii. Two test images equal on the square of this radius around a pixel
// give it the same FLIP value, to the bit.
int flip_radius(double pixels_per_degree = kFlipDefaultPixelsPerDegree);

// flip()'s map at the pixels where `needed` (one byte a pixel) is not 0, the
// same bits there, and 0 elsewhere: it costs only the rows and columns near
// the needed pixels. Throws as flip() does, and for a mask of another size.
core::ImageF flip_map_within(const core::ImageF& reference, const core::ImageF& test,
                             const std::vector<uint8_t>& needed,
                             double pixels_per_degree = kFlipDefaultPixelsPerDegree);
core::ImageF flip_map_within(const FlipReference& reference, const core::ImageF& test,
                             const std::vector<uint8_t>& needed);

// An sRGB-encoded image (an 8-bit PNG read as v / 255) decoded to linear
// values (IEC 61966-2-1), as FLIP's LDR inputs are: every channel but a 4th
// (alpha), which is kept.
core::ImageF linear_from_srgb(const core::ImageF& encoded);

namespace detail {
// flip() on a given vector width (it takes the widest this CPU runs); every
// path gives the same bits. Throws std::invalid_argument for a path this CPU
// does not run, as for flip()'s bad arguments.
FlipResult flip_on(SimdPath path, const core::ImageF& reference, const core::ImageF& test,
                   double pixels_per_degree = kFlipDefaultPixelsPerDegree);
core::ImageF flip_map_within_on(SimdPath path, const core::ImageF& reference,
                                const core::ImageF& test, const std::vector<uint8_t>& needed,
                                double pixels_per_degree = kFlipDefaultPixelsPerDegree);
FlipResult flip_on(SimdPath path, const FlipReference& reference, const core::ImageF& test);
core::ImageF flip_map_within_on(SimdPath path, const FlipReference& reference,
                                const core::ImageF& test, const std::vector<uint8_t>& needed);
}  // namespace detail

}  // namespace sb::metrics
