#include "metrics/flip_filters.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sb::metrics::flip_detail {

namespace {

// The contrast sensitivity functions as Gaussians in the spatial domain,
// a * sqrt(pi / b) * exp(-pi^2 x^2 / b) with x in degrees (the paper's
// table): Y and Cx one each, Cz the sum of two.
struct Csf {
  double a1, b1, a2, b2;
};
constexpr Csf kCsfY{1.0, 0.0047, 0.0, 1e-5}, kCsfCx{1.0, 0.0053, 0.0, 1e-5},
    kCsfCz{34.1, 0.04, 13.5, 0.025};

}  // namespace

SpatialFilters spatial_filters(double ppd) {
  constexpr double pi = std::numbers::pi;
  const double b_max = std::max({kCsfY.b1, kCsfCx.b1, kCsfCz.b1, kCsfY.b2, kCsfCx.b2, kCsfCz.b2});
  SpatialFilters f;
  f.radius = static_cast<int>(std::ceil(3.0 * std::sqrt(b_max / (2.0 * pi * pi)) * ppd));
  const int n = 2 * f.radius + 1;
  std::vector<double> y(n), cx(n), cz1(n), cz2(n);
  auto gauss = [&](double x2, double a, double b) {
    return a * std::sqrt(pi / b) * std::exp(-pi * pi * x2 / b);
  };
  double sy = 0, scx = 0, s1 = 0, s2 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = (i - f.radius) / ppd, x2 = x * x;
    y[i] = gauss(x2, kCsfY.a1, kCsfY.b1);
    cx[i] = gauss(x2, kCsfCx.a1, kCsfCx.b1);
    cz1[i] = std::sqrt(kCsfCz.a1 * std::sqrt(pi / kCsfCz.b1)) * std::exp(-pi * pi * x2 / kCsfCz.b1);
    cz2[i] = std::sqrt(kCsfCz.a2 * std::sqrt(pi / kCsfCz.b2)) * std::exp(-pi * pi * x2 / kCsfCz.b2);
    sy += y[i], scx += cx[i], s1 += cz1[i], s2 += cz2[i];
  }
  const double cz_norm = 1.0 / std::sqrt(s1 * s1 + s2 * s2);
  for (int i = 0; i < n; ++i) {
    f.y.push_back(static_cast<float>(y[i] / sy));
    f.cx.push_back(static_cast<float>(cx[i] / scx));
    f.cz1.push_back(static_cast<float>(cz1[i] * cz_norm));
    f.cz2.push_back(static_cast<float>(cz2[i] * cz_norm));
  }
  return f;
}

FeatureFilters feature_filters(double ppd) {
  const double sd = 0.5 * kFeatureWidth * ppd;
  FeatureFilters f;
  f.radius = static_cast<int>(std::ceil(3.0 * sd));
  const int n = 2 * f.radius + 1;
  std::vector<double> g(n), dg(n), ddg(n);
  double sg = 0, dpos = 0, dneg = 0, ddpos = 0, ddneg = 0;
  for (int i = 0; i < n; ++i) {
    const double x = i - f.radius;
    g[i] = std::exp(-x * x / (2.0 * sd * sd));
    dg[i] = -x * g[i];
    ddg[i] = (x * x / (sd * sd) - 1.0) * g[i];
    sg += g[i];
    (dg[i] > 0 ? dpos : dneg) += std::abs(dg[i]);
    (ddg[i] > 0 ? ddpos : ddneg) += std::abs(ddg[i]);
  }
  for (int i = 0; i < n; ++i) {
    f.g.push_back(static_cast<float>(g[i] / sg));
    f.dg.push_back(static_cast<float>(dg[i] / (dg[i] > 0 ? dpos : dneg)));
    f.ddg.push_back(static_cast<float>(ddg[i] / (ddg[i] > 0 ? ddpos : ddneg)));
  }
  return f;
}

}  // namespace sb::metrics::flip_detail
