#include "metrics/flip_colour.h"

#include <cmath>

#include "metrics/flip.h"

namespace sb::metrics {

using core::ImageF;

namespace flip_detail {

std::array<std::array<float, 3>, 3> inverse(const double m[3][3]) {
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  std::array<std::array<float, 3>, 3> r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      // The cofactor of m[j][i], over the determinant.
      const int a = (j + 1) % 3, b = (j + 2) % 3, c = (i + 1) % 3, d = (i + 2) % 3;
      r[i][j] = static_cast<float>((m[a][c] * m[b][d] - m[a][d] * m[b][c]) / det);
    }
  return r;
}

float max_colour_distance() {
  const Colour green = xyz_to_hunt_lab(rgb_to_xyz(0, 1, 0));
  const Colour blue = xyz_to_hunt_lab(rgb_to_xyz(0, 0, 1));
  return std::pow(hyab(green, blue), kQc);
}

}  // namespace flip_detail

ImageF linear_from_srgb(const ImageF& encoded) {
  ImageF out = encoded;
  for (std::size_t i = 0; i < out.data.size(); ++i) {
    if (out.channels == 4 && i % 4 == 3) continue;
    const float v = out.data[i];
    out.data[i] = v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
  }
  return out;
}

}  // namespace sb::metrics
