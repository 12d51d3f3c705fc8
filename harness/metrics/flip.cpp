#include "metrics/flip.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace sb::metrics {

using core::ImageF;

namespace {

// One channel of an image, row by row. Not zeroed when made: every pass
// writes each value before it is read, and zeroing the planes (about 120 MB
// at 1920x1080) took a quarter of the time.
class Plane {
 public:
  explicit Plane(std::size_t n) : values_(new float[n]) {}
  float& operator[](std::size_t i) { return values_[i]; }
  const float& operator[](std::size_t i) const { return values_[i]; }
  const float* data() const { return values_.get(); }

 private:
  std::unique_ptr<float[]> values_;
};

// ---------------------------------------------------------------- math
//
// log2, exp2 and the cube root as plain arithmetic on the float's bits, so
// that the per-pixel loops vectorise (the C library's calls do not): about
// 1e-7 relative error, far below the 1e-4 the maps are held to.

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

// ---------------------------------------------------------------- colour

// Linear sRGB (D65) to CIE XYZ, and its inverse.
constexpr double kRgbToXyz[3][3] = {
    {10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
    {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
    {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0}};

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

// The reference white (D65) as XYZ, as the paper's reference implementation
// gives it (its published values depend on these digits).
constexpr float kWhite[3] = {0.950428545f, 1.0f, 1.088900371f};

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

constexpr float kQc = 0.7f, kPc = 0.4f, kPt = 0.95f, kQf = 0.5f, kFeatureWidth = 0.082f;
static_assert(kQf == 0.5f, "the feature difference is taken as a square root below");

// The largest colour distance, green to blue, raised to q_c.
float max_colour_distance() {
  const Colour green = xyz_to_hunt_lab(rgb_to_xyz(0, 1, 0));
  const Colour blue = xyz_to_hunt_lab(rgb_to_xyz(0, 0, 1));
  return std::pow(hyab(green, blue), kQc);
}

// ---------------------------------------------------------------- filters

// The contrast sensitivity functions as Gaussians in the spatial domain,
// a * sqrt(pi / b) * exp(-pi^2 x^2 / b) with x in degrees (the paper's
// table): Y and Cx one each, Cz the sum of two.
struct Csf {
  double a1, b1, a2, b2;
};
constexpr Csf kCsfY{1.0, 0.0047, 0.0, 1e-5}, kCsfCx{1.0, 0.0053, 0.0, 1e-5},
    kCsfCz{34.1, 0.04, 13.5, 0.025};

struct SpatialFilters {
  int radius = 0;
  std::vector<float> y, cx, cz1, cz2;  // 2 * radius + 1 taps each
};

// 1D filters whose outer products make the 2D ones: Y's and Cx's normalised
// to sum 1; Cz's two Gaussians each the square root of its 2D one (so that
// cz1(x) cz1(y) + cz2(x) cz2(y) is the sum of two 2D Gaussians), scaled
// together so that the 2D sum is 1.
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

struct FeatureFilters {
  int radius = 0;
  std::vector<float> g, dg, ddg;  // Gaussian, its first and second derivative
};

// sd = 0.5 * 0.082 degrees in pixels, radius 3 sd. The Gaussian sums to 1;
// each derivative's positive taps sum to 1 and its negative taps to -1.
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

// ---------------------------------------------------------------- passes

// Runs body(y0, y1) over blocks of rows in parallel.
template <class Body>
void for_rows(int height, Body body) {
  tbb::parallel_for(tbb::blocked_range<int>(0, height, 8),
                    [&](const tbb::blocked_range<int>& r) { body(r.begin(), r.end()); });
}

// A row with `radius` copies of its edge values on either side, so that a
// filter over it needs no clamping.
void pad_row(const float* in, int width, int radius, float* pad) {
  std::fill(pad, pad + radius, in[0]);
  std::copy(in, in + width, pad + radius);
  std::fill(pad + radius + width, pad + 2 * radius + width, in[width - 1]);
}

// out[x] = sum_k taps[k] * in[clamp(x + k - radius)] for one row, from the
// row padded by pad_row: one tap at a time over the whole row (a loop the
// compiler vectorises).
void filter_padded(const float* pad, int width, const std::vector<float>& taps, float* out) {
  // The first tap sets, the others add (0 + a is a: the same sums as from 0).
  for (int x = 0; x < width; ++x) out[x] = taps[0] * pad[x];
  for (std::size_t k = 1; k < taps.size(); ++k) {
    const float t = taps[k];
    const float* p = pad + k;
    for (int x = 0; x < width; ++x) out[x] += t * p[x];
  }
}

// out row y = sum_k taps[k] * rows[clamp(y + k - radius)].
void filter_column(const Plane& in, int width, int height, int y, const std::vector<float>& taps,
                   float* out) {
  const int radius = static_cast<int>(taps.size() / 2);
  for (std::size_t k = 0; k < taps.size(); ++k) {
    const int yy = std::clamp(y + static_cast<int>(k) - radius, 0, height - 1);
    const float t = taps[k];
    const float* p = in.data() + static_cast<std::size_t>(yy) * width;
    if (k == 0) {  // the first tap sets, the others add, as in filter_padded
      for (int x = 0; x < width; ++x) out[x] = t * p[x];
    } else {
      for (int x = 0; x < width; ++x) out[x] += t * p[x];
    }
  }
}

// A value clamped to [0, 1], NaN read as 0: a technique's broken pixel is
// black to FLIP (its other metrics count it as non-finite) and never
// reaches the float-to-int conversions of the fast math.
float unit(float v) { return v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; }

// One image as FLIP reads it: YCxCz planes and the luminance.
struct Opponent {
  Plane y, cx, cz, luminance;
};

Opponent to_opponent(const ImageF& img) {
  const std::size_t n = img.pixel_count();
  Opponent o{Plane(n), Plane(n), Plane(n), Plane(n)};
  for_rows(img.height, [&](int y0, int y1) {
    for (std::size_t i = static_cast<std::size_t>(y0) * img.width;
         i < static_cast<std::size_t>(y1) * img.width; ++i) {
      const float* p = &img.data[i * img.channels];
      const bool grey = img.channels == 1;
      const float r = unit(p[0]);
      const float g = grey ? r : unit(p[1]);
      const float b = grey ? r : unit(p[2]);
      const Colour xyz = rgb_to_xyz(r, g, b);
      const float xn = xyz.a / kWhite[0], yn = xyz.b, zn = xyz.c / kWhite[2];
      o.y[i] = 116.0f * yn - 16.0f;
      o.cx[i] = 500.0f * (xn - yn);
      o.cz[i] = 200.0f * (yn - zn);
      o.luminance[i] = yn;
    }
  });
  return o;
}

// The colour pipeline's horizontal pass: Y and Cx by their filters, Cz by
// each of its two.
struct SpatialRows {
  Plane y, cx, cz1, cz2;
};

SpatialRows spatial_rows(const Opponent& o, int width, int height, const SpatialFilters& f) {
  const std::size_t n = static_cast<std::size_t>(width) * height;
  SpatialRows s{Plane(n), Plane(n), Plane(n), Plane(n)};
  for_rows(height, [&](int y0, int y1) {
    std::vector<float> pad(static_cast<std::size_t>(width) + 2 * f.radius);
    for (int y = y0; y < y1; ++y) {
      const std::size_t row = static_cast<std::size_t>(y) * width;
      pad_row(&o.y[row], width, f.radius, pad.data());
      filter_padded(pad.data(), width, f.y, &s.y[row]);
      pad_row(&o.cx[row], width, f.radius, pad.data());
      filter_padded(pad.data(), width, f.cx, &s.cx[row]);
      pad_row(&o.cz[row], width, f.radius, pad.data());
      filter_padded(pad.data(), width, f.cz1, &s.cz1[row]);
      filter_padded(pad.data(), width, f.cz2, &s.cz2[row]);
    }
  });
  return s;
}

// The feature pipeline's horizontal pass: first and second x-derivatives
// and the Gaussian of the luminance.
struct FeatureRows {
  Plane dx, ddx, g;
};

FeatureRows feature_rows(const Plane& luminance, int width, int height, const FeatureFilters& f) {
  const std::size_t n = static_cast<std::size_t>(width) * height;
  FeatureRows s{Plane(n), Plane(n), Plane(n)};
  for_rows(height, [&](int y0, int y1) {
    std::vector<float> pad(static_cast<std::size_t>(width) + 2 * f.radius);
    for (int y = y0; y < y1; ++y) {
      const std::size_t row = static_cast<std::size_t>(y) * width;
      pad_row(&luminance[row], width, f.radius, pad.data());
      filter_padded(pad.data(), width, f.dg, &s.dx[row]);
      filter_padded(pad.data(), width, f.ddg, &s.ddx[row]);
      filter_padded(pad.data(), width, f.g, &s.g[row]);
    }
  });
  return s;
}

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

}  // namespace

ImageF linear_from_srgb(const ImageF& encoded) {
  ImageF out = encoded;
  for (std::size_t i = 0; i < out.data.size(); ++i) {
    if (out.channels == 4 && i % 4 == 3) continue;
    const float v = out.data[i];
    out.data[i] = v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
  }
  return out;
}

FlipResult flip(const ImageF& reference, const ImageF& test, double pixels_per_degree) {
  auto channels_ok = [](const ImageF& i) {
    return i.channels == 1 || i.channels == 3 || i.channels == 4;
  };
  if (reference.width != test.width || reference.height != test.height)
    throw std::invalid_argument("flip: the images differ in size");
  if (!channels_ok(reference) || !channels_ok(test))
    throw std::invalid_argument("flip: expected 1, 3 or 4 channels");
  if (reference.pixel_count() == 0) throw std::invalid_argument("flip: empty image");
  if (!(pixels_per_degree > 0 && pixels_per_degree <= 1000))
    throw std::invalid_argument("flip: pixels per degree must be in (0, 1000], not " +
                                std::to_string(pixels_per_degree));

  const int w = reference.width, h = reference.height;
  const SpatialFilters spatial = spatial_filters(pixels_per_degree);
  const FeatureFilters features = feature_filters(pixels_per_degree);
  const Opponent ref = to_opponent(reference), tst = to_opponent(test);
  const SpatialRows ref_rows = spatial_rows(ref, w, h, spatial);
  const SpatialRows tst_rows = spatial_rows(tst, w, h, spatial);
  const FeatureRows ref_features = feature_rows(ref.luminance, w, h, features);
  const FeatureRows tst_features = feature_rows(tst.luminance, w, h, features);

  const auto xyz_to_rgb = inverse(kRgbToXyz);
  const float cmax = max_colour_distance(), pccmax = kPc * cmax;
  const float feature_norm = 1.0f / std::sqrt(2.0f);
  // The remapping's two slopes: [0, p_c cmax) onto [0, p_t), the rest onto [p_t, 1].
  const float below = kPt / pccmax, above = (1.0f - kPt) / (cmax - pccmax);
  FlipResult result;
  result.error = ImageF(w, h, 1);
  std::vector<double> row_sums(h, 0.0);
  for_rows(h, [&](int y0, int y1) {
    // Per side: Y, Cx, Cz (two parts), then dx, ddx, dy, ddy.
    std::vector<float> buf(static_cast<std::size_t>(w) * 16);
    auto line = [&](int i) { return buf.data() + static_cast<std::size_t>(i) * w; };
    for (int y = y0; y < y1; ++y) {
      for (int side = 0; side < 2; ++side) {
        const SpatialRows& s = side == 0 ? ref_rows : tst_rows;
        const FeatureRows& f = side == 0 ? ref_features : tst_features;
        float* o = line(side * 8);
        filter_column(s.y, w, h, y, spatial.y, o);
        filter_column(s.cx, w, h, y, spatial.cx, o + w);
        filter_column(s.cz1, w, h, y, spatial.cz1, o + 2 * w);
        filter_column(s.cz2, w, h, y, spatial.cz2, o + 3 * w);
        filter_column(f.dx, w, h, y, features.g, o + 4 * w);
        filter_column(f.ddx, w, h, y, features.g, o + 5 * w);
        filter_column(f.g, w, h, y, features.dg, o + 6 * w);
        filter_column(f.g, w, h, y, features.ddg, o + 7 * w);
      }
      float* out = &result.error.data[static_cast<std::size_t>(y) * w];
      // Each side's Hunt L*a*b* and feature magnitudes, over the row (loops
      // the compiler vectorises), into the side's first six lines.
      for (int side = 0; side < 2; ++side) {
        float* o = line(side * 8);
        float *ly = o, *la = o + w, *lb = o + 2 * w, *edge = o + 4 * w, *point = o + 5 * w;
        for (int x = 0; x < w; ++x) {
          const Colour lab = filtered_to_hunt_lab(ly[x], la[x], lb[x] + o[3 * w + x], xyz_to_rgb);
          ly[x] = lab.a, la[x] = lab.b, lb[x] = lab.c;
        }
        for (int x = 0; x < w; ++x) {
          const float dx = edge[x], ddx = point[x], dy = o[6 * w + x], ddy = o[7 * w + x];
          edge[x] = std::sqrt(dx * dx + dy * dy);
          point[x] = std::sqrt(ddx * ddx + ddy * ddy);
        }
      }
      const float *r = line(0), *t = line(8);
      float* colour = line(6);  // the reference's dy, no longer needed
      // Locals, not the lambda's references: a choice between values in
      // registers is a select, one between loads is a branch.
      const float knee = pccmax, slope_below = below, slope_above = above;
      for (int x = 0; x < w; ++x) {
        const float dl = r[x] - t[x], da = r[w + x] - t[w + x], db = r[2 * w + x] - t[2 * w + x];
        const float c = fast_pow(std::abs(dl) + std::sqrt(da * da + db * db), kQc);
        colour[x] = c < knee ? c * slope_below : kPt + (c - knee) * slope_above;
      }
      for (int x = 0; x < w; ++x) {
        // q_f = 0.5: the square root.
        const float edge = std::abs(r[4 * w + x] - t[4 * w + x]);
        const float point = std::abs(r[5 * w + x] - t[5 * w + x]);
        const float feature = std::sqrt(feature_norm * (edge > point ? edge : point));
        out[x] = fast_pow(colour[x], 1.0f - feature);
      }
      double sum = 0;
      for (int x = 0; x < w; ++x) sum += out[x];
      row_sums[y] = sum;
    }
  });
  double total = 0;
  for (double s : row_sums) total += s;  // in row order: the same sum on any thread count
  result.mean = total / static_cast<double>(reference.pixel_count());
  return result;
}

}  // namespace sb::metrics
