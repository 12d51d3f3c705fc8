#pragma once
// FLIP's colour pipeline (metrics/flip.h): linear RGB to CIE XYZ, to the
// opponent space the contrast sensitivity filters work in and back, to
// L*a*b* with the Hunt adjustment, the HyAB distance, and the remapping of
// that distance to [0, 1]. The per-pixel parts are always inlined, into each
// vector width's band (flip_tile.cpp).
#include <algorithm>
#include <array>
#include <cmath>

#include "metrics/flip_math.h"

namespace sb::metrics::flip_detail {

// Linear sRGB (D65) to CIE XYZ.
inline constexpr double kRgbToXyz[3][3] = {
    {10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
    {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
    {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0}};

// The reference white (D65) as XYZ, as the paper's reference implementation
// gives it (its published values depend on these digits).
inline constexpr float kWhite[3] = {0.950428545f, 1.0f, 1.088900371f};

struct Colour {
  float a, b, c;
};

[[gnu::always_inline]] inline Colour rgb_to_xyz(float r, float g, float b) {
  auto row = [&](int i) {
    return static_cast<float>(kRgbToXyz[i][0]) * r + static_cast<float>(kRgbToXyz[i][1]) * g +
           static_cast<float>(kRgbToXyz[i][2]) * b;
  };
  return {row(0), row(1), row(2)};
}

// CIELAB's f(t): the cube root above (6/29)^3, a line below.
[[gnu::always_inline]] inline float lab_f(float t) {
  constexpr float kDelta = 6.0f / 29.0f;
  const float cube_root = fast_cbrt(t > 1e-30f ? t : 1e-30f);  // both sides, as in fast_pow
  const float linear = t * (1.0f / (3.0f * kDelta * kDelta)) + 4.0f / 29.0f;
  return t > kDelta * kDelta * kDelta ? cube_root : linear;
}

// XYZ to L*a*b* with the Hunt adjustment (a*, b* scaled by 0.01 L*).
[[gnu::always_inline]] inline Colour xyz_to_hunt_lab(Colour xyz) {
  const float fx = lab_f(xyz.a / kWhite[0]), fy = lab_f(xyz.b), fz = lab_f(xyz.c / kWhite[2]);
  const float l = 116.0f * fy - 16.0f;
  return {l, 0.01f * l * 500.0f * (fx - fy), 0.01f * l * 200.0f * (fy - fz)};
}

// HyAB: city-block in L, Euclidean in (a, b).
[[gnu::always_inline]] inline float hyab(Colour p, Colour q) {
  return std::abs(p.a - q.a) + std::sqrt((p.b - q.b) * (p.b - q.b) + (p.c - q.c) * (p.c - q.c));
}

// The colour difference's exponent q_c, and its remapping: the fraction p_c
// of the largest distance maps to p_t.
inline constexpr float kQc = 0.7f, kPc = 0.4f, kPt = 0.95f;

// A filtered YCxCz colour back to linear RGB, clamped to [0, 1], then to
// Hunt-adjusted L*a*b*.
[[gnu::always_inline]] inline Colour filtered_to_hunt_lab(
    float y, float cx, float cz, const std::array<std::array<float, 3>, 3>& xyz_to_rgb) {
  const float fy = (y + 16.0f) / 116.0f;
  const Colour xyz{(fy + cx / 500.0f) * kWhite[0], fy, (fy - cz / 200.0f) * kWhite[2]};
  float rgb[3];
  for (int i = 0; i < 3; ++i)
    rgb[i] = std::clamp(
        xyz_to_rgb[i][0] * xyz.a + xyz_to_rgb[i][1] * xyz.b + xyz_to_rgb[i][2] * xyz.c, 0.0f, 1.0f);
  return xyz_to_hunt_lab(rgb_to_xyz(rgb[0], rgb[1], rgb[2]));
}

// The inverse of a 3x3 matrix (kRgbToXyz's: XYZ to linear sRGB).
std::array<std::array<float, 3>, 3> inverse(const double m[3][3]);

// The largest colour distance, green to blue, raised to q_c: the
// remapping's scale.
float max_colour_distance();

}  // namespace sb::metrics::flip_detail
