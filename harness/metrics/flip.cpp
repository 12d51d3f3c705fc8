#include "metrics/flip.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "metrics/simd_path.h"

namespace sb::metrics {

using core::ImageF;

namespace {

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
//
// The image is cut into tiles: bands of rows by columns, one task each. A
// tile slides down its rows keeping, per image and per filtered quantity, a
// ring of the 2 radius + 1 rows that the vertical filters of the current row
// read, filtered horizontally as they enter. So no full-size intermediate
// plane is made: a tile's rings (about 300 KB for 256 columns) stay in its
// core's cache, where the planes (120 MB at 1920x1080) went to memory and
// page faults. Every output value is computed as before, in the same order,
// whatever the tiling, so the bits depend neither on it nor on the threads.
//
// Everything a band runs is inlined into it, and the band is compiled for
// three vector widths (baseline x86-64, AVX2, AVX-512) and picked at run
// time, as SSIM's kernels are (ssim_kernels.h); -ffp-contract=off keeps
// their bits the same.

// Per image: Y, Cx and the two parts of Cz (colour), the luminance's x
// derivatives and Gaussian (features), all filtered horizontally.
enum Quantity { kY, kCx, kCz1, kCz2, kDx, kDdx, kG, kQuantities };

struct Setup {
  const ImageF* image[2];  // the reference, the test
  int width, height;
  SpatialFilters spatial;
  FeatureFilters features;
  int radius;  // the larger filter radius: the rings' half height
  std::array<std::array<float, 3>, 3> xyz_to_rgb;
  float knee, slope_below, slope_above, feature_norm;
};

// A thread's rows, reused from tile to tile, `width` columns wide.
class Scratch {
 public:
  Scratch(int width, int radius)
      : width_(width),
        slots_(2 * radius + 1),
        padded_(static_cast<std::size_t>(width) + 2 * static_cast<std::size_t>(radius)),
        rings_(2 * kQuantities * static_cast<std::size_t>(slots_) * width),
        pads_(4 * padded_),
        lines_(16 * static_cast<std::size_t>(width)),
        sources_(static_cast<std::size_t>(slots_)) {}
  int slots() const { return slots_; }
  float* ring(int side, int quantity, int slot) {
    return rings_.data() +
           ((static_cast<std::size_t>(side) * kQuantities + quantity) * slots_ + slot) * width_;
  }
  // The padded opponent rows of the row being filtered: Y, Cx, Cz, luminance.
  float* pad(int i) { return pads_.data() + static_cast<std::size_t>(i) * padded_; }
  // The vertical pass's output: per side Y, Cx, Cz1, Cz2, dx, ddx, dy, ddy.
  float* line(int i) { return lines_.data() + static_cast<std::size_t>(i) * width_; }
  // A filter's source rows, one per tap.
  const float** sources() { return sources_.data(); }

 private:
  int width_, slots_;
  std::size_t padded_;
  std::vector<float> rings_, pads_, lines_;
  std::vector<const float*> sources_;
};

// A value clamped to [0, 1], NaN read as 0: a technique's broken pixel is
// black to FLIP (its other metrics count it as non-finite) and never
// reaches the float-to-int conversions of the fast math.
[[gnu::always_inline]] inline float unit(float v) {
  return v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
}

// `Lanes` floats as one value of GCC's generic vectors: one register of
// the target (4 for SSE2, 8 for AVX2, 16 for AVX-512). Their functions are
// always inlined, so that how such a value would be passed between
// functions built for different targets (what -Wpsabi warns of) never
// arises.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
template <int Lanes>
struct Vector {
  typedef float Type __attribute__((vector_size(Lanes * sizeof(float))));
  static_assert(sizeof(Type) == Lanes * sizeof(float), "a vector, not a float");
  [[gnu::always_inline]] static Type load(const float* p) {
    Type v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  [[gnu::always_inline]] static void store(float* p, const Type& v) {
    std::memcpy(p, &v, sizeof v);
  }
};

// out[i] = sum_k taps[k] * src[k][i] for i < n, each sum begun with tap 0
// and added up in tap order (the bits of a loop over the taps). Four
// registers of outputs at a time stay in registers over all the taps: only
// the sources are loaded, where a loop of taps outside would load and store
// the sums once per tap.
template <int Lanes>
[[gnu::always_inline]] inline void sum_of_taps(const float* const* src,
                                               const std::vector<float>& taps, int n, float* out) {
  using V = Vector<Lanes>;
  const std::size_t count = taps.size();
  int i = 0;
  for (; i + 4 * Lanes <= n; i += 4 * Lanes) {
    const float t0 = taps[0];
    typename V::Type a0 = t0 * V::load(src[0] + i), a1 = t0 * V::load(src[0] + i + Lanes),
                     a2 = t0 * V::load(src[0] + i + 2 * Lanes),
                     a3 = t0 * V::load(src[0] + i + 3 * Lanes);
    for (std::size_t k = 1; k < count; ++k) {
      const float t = taps[k];
      const float* p = src[k] + i;
      a0 += t * V::load(p);
      a1 += t * V::load(p + Lanes);
      a2 += t * V::load(p + 2 * Lanes);
      a3 += t * V::load(p + 3 * Lanes);
    }
    V::store(out + i, a0);
    V::store(out + i + Lanes, a1);
    V::store(out + i + 2 * Lanes, a2);
    V::store(out + i + 3 * Lanes, a3);
  }
  for (; i + Lanes <= n; i += Lanes) {
    typename V::Type a = taps[0] * V::load(src[0] + i);
    for (std::size_t k = 1; k < count; ++k) a += taps[k] * V::load(src[k] + i);
    V::store(out + i, a);
  }
  for (; i < n; ++i) {
    float a = taps[0] * src[0][i];
    for (std::size_t k = 1; k < count; ++k) a += taps[k] * src[k][i];
    out[i] = a;
  }
}
#pragma GCC diagnostic pop

// out[x] = sum_k taps[k] * pad[x + k].
template <int Lanes>
[[gnu::always_inline]] inline void filter_row(Scratch& sc, const float* pad, int width,
                                              const std::vector<float>& taps, float* out) {
  const float** src = sc.sources();
  for (std::size_t k = 0; k < taps.size(); ++k) src[k] = pad + k;
  sum_of_taps<Lanes>(src, taps, width, out);
}

// Columns [x0, x1) of image row `row` of one side, to YCxCz and luminance
// (from `radius` columns before to `radius` after, the edge columns
// repeated beyond the image), filtered horizontally into ring slot `slot`.
template <int Lanes>
[[gnu::always_inline]] inline void enter_row(const Setup& s, Scratch& sc, int side, int row,
                                             int slot, int x0, int x1) {
  const ImageF& img = *s.image[side];
  const int w = x1 - x0, r = s.radius;
  float *py = sc.pad(0), *pcx = sc.pad(1), *pcz = sc.pad(2), *plum = sc.pad(3);
  const bool grey = img.channels == 1;
  const std::size_t nc = static_cast<std::size_t>(img.channels);
  const float* in = &img.data[static_cast<std::size_t>(row) * s.width * nc];
  // The pixels into planes first (red, green, blue in the Y, Cx, Cz pads),
  // so that the conversion below is a loop over planes, which vectorises.
  const int n = w + 2 * r;
  for (int i = 0; i < n; ++i) {
    const int column = std::clamp(x0 - r + i, 0, s.width - 1);
    const float* p = in + static_cast<std::size_t>(column) * nc;
    py[i] = unit(p[0]);
    pcx[i] = grey ? py[i] : unit(p[1]);
    pcz[i] = grey ? py[i] : unit(p[2]);
  }
  for (int i = 0; i < n; ++i) {
    const Colour xyz = rgb_to_xyz(py[i], pcx[i], pcz[i]);
    const float xn = xyz.a / kWhite[0], yn = xyz.b, zn = xyz.c / kWhite[2];
    py[i] = 116.0f * yn - 16.0f;
    pcx[i] = 500.0f * (xn - yn);
    pcz[i] = 200.0f * (yn - zn);
    plum[i] = yn;
  }
  // A filter of radius q reads the pad from r - q.
  const int qs = s.spatial.radius, qf = s.features.radius;
  filter_row<Lanes>(sc, py + (r - qs), w, s.spatial.y, sc.ring(side, kY, slot));
  filter_row<Lanes>(sc, pcx + (r - qs), w, s.spatial.cx, sc.ring(side, kCx, slot));
  filter_row<Lanes>(sc, pcz + (r - qs), w, s.spatial.cz1, sc.ring(side, kCz1, slot));
  filter_row<Lanes>(sc, pcz + (r - qs), w, s.spatial.cz2, sc.ring(side, kCz2, slot));
  filter_row<Lanes>(sc, plum + (r - qf), w, s.features.dg, sc.ring(side, kDx, slot));
  filter_row<Lanes>(sc, plum + (r - qf), w, s.features.ddg, sc.ring(side, kDdx, slot));
  filter_row<Lanes>(sc, plum + (r - qf), w, s.features.g, sc.ring(side, kG, slot));
}

// out = sum_k taps[k] * (the ring's row y + k - q, q the taps' radius),
// the rows named by their place in the tile (`first` is slot 0's).
template <int Lanes>
[[gnu::always_inline]] inline void filter_column(Scratch& sc, int side, int quantity, int y,
                                                 int first, const std::vector<float>& taps,
                                                 int width, float* out) {
  const int q = static_cast<int>(taps.size() / 2);
  const float** src = sc.sources();
  for (std::size_t k = 0; k < taps.size(); ++k)
    src[k] = sc.ring(side, quantity, (y + static_cast<int>(k) - q - first) % sc.slots());
  sum_of_taps<Lanes>(src, taps, width, out);
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

// FLIP of output row y from the rings: the vertical filters, each side's
// Hunt L*a*b* and feature magnitudes, then the colour and feature
// differences. Returns the row's sum.
template <int Lanes>
[[gnu::always_inline]] inline void flip_row(const Setup& s, Scratch& sc, int y, int first, int w,
                                            float* out) {
  for (int side = 0; side < 2; ++side) {
    float* o = sc.line(side * 8);
    filter_column<Lanes>(sc, side, kY, y, first, s.spatial.y, w, o);
    filter_column<Lanes>(sc, side, kCx, y, first, s.spatial.cx, w, o + w);
    filter_column<Lanes>(sc, side, kCz1, y, first, s.spatial.cz1, w, o + 2 * w);
    filter_column<Lanes>(sc, side, kCz2, y, first, s.spatial.cz2, w, o + 3 * w);
    filter_column<Lanes>(sc, side, kDx, y, first, s.features.g, w, o + 4 * w);
    filter_column<Lanes>(sc, side, kDdx, y, first, s.features.g, w, o + 5 * w);
    filter_column<Lanes>(sc, side, kG, y, first, s.features.dg, w, o + 6 * w);
    filter_column<Lanes>(sc, side, kG, y, first, s.features.ddg, w, o + 7 * w);
  }
  // Each side's Hunt L*a*b* and feature magnitudes, over the row (loops the
  // compiler vectorises), into the side's first six lines.
  for (int side = 0; side < 2; ++side) {
    float* o = sc.line(side * 8);
    float *ly = o, *la = o + w, *lb = o + 2 * w, *edge = o + 4 * w, *point = o + 5 * w;
    for (int x = 0; x < w; ++x) {
      const Colour lab = filtered_to_hunt_lab(ly[x], la[x], lb[x] + o[3 * w + x], s.xyz_to_rgb);
      ly[x] = lab.a, la[x] = lab.b, lb[x] = lab.c;
    }
    for (int x = 0; x < w; ++x) {
      const float dx = edge[x], ddx = point[x], dy = o[6 * w + x], ddy = o[7 * w + x];
      edge[x] = std::sqrt(dx * dx + dy * dy);
      point[x] = std::sqrt(ddx * ddx + ddy * ddy);
    }
  }
  const float *r = sc.line(0), *t = sc.line(8);
  float* colour = sc.line(6);  // the reference's dy, no longer needed
  // Locals, not references: a choice between values in registers is a
  // select, one between loads is a branch.
  const float knee = s.knee, slope_below = s.slope_below, slope_above = s.slope_above;
  const float feature_norm = s.feature_norm;
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
}

// A tile's rows and columns.
struct Tile {
  int y0, y1, x0, x1;
};

// Tile row v (an image row, or beyond the image its edge row) of both
// images into the rings.
template <int Lanes>
[[gnu::always_inline]] inline void enter_rows(const Setup& s, Scratch& sc, const Tile& t, int v,
                                              int first) {
  const int row = std::clamp(v, 0, s.height - 1), slot = (v - first) % sc.slots();
  enter_row<Lanes>(s, sc, 0, row, slot, t.x0, t.x1);
  enter_row<Lanes>(s, sc, 1, row, slot, t.x0, t.x1);
}

// The ring first holds the rows y0 - radius ... y0 + radius - 1, then takes
// one row per output row.
template <int Lanes>
[[gnu::always_inline]] inline void tile_body(const Setup& s, Scratch& sc, const Tile& t,
                                             float* error) {
  const int r = s.radius, first = t.y0 - r;
  for (int v = t.y0 - r; v < t.y0 + r; ++v) enter_rows<Lanes>(s, sc, t, v, first);
  for (int y = t.y0; y < t.y1; ++y) {
    enter_rows<Lanes>(s, sc, t, y + r, first);
    flip_row<Lanes>(s, sc, y, first, t.x1 - t.x0,
                    error + static_cast<std::size_t>(y) * s.width + t.x0);
  }
}

void tile_baseline(const Setup& s, Scratch& sc, const Tile& t, float* error) {
  tile_body<4>(s, sc, t, error);
}
#if defined(__x86_64__)
[[gnu::target("avx2")]] void tile_avx2(const Setup& s, Scratch& sc, const Tile& t, float* error) {
  tile_body<8>(s, sc, t, error);
}
[[gnu::target("avx512f,prefer-vector-width=512")]] void tile_avx512(const Setup& s, Scratch& sc,
                                                                    const Tile& t, float* error) {
  tile_body<16>(s, sc, t, error);
}
#endif

void tile_on(detail::SimdPath path, const Setup& s, Scratch& sc, const Tile& t, float* error) {
#if defined(__x86_64__)
  if (path == detail::SimdPath::Avx512) return tile_avx512(s, sc, t, error);
  if (path == detail::SimdPath::Avx2) return tile_avx2(s, sc, t, error);
#endif
  (void)path;  // elsewhere every path is the baseline
  tile_baseline(s, sc, t, error);
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

FlipResult detail::flip_on(SimdPath path, const ImageF& reference, const ImageF& test,
                           double pixels_per_degree) {
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
  if (!runs_here(path)) throw std::invalid_argument("flip: this CPU has no " + to_string(path));

  const int w = reference.width, h = reference.height;
  Setup s{{&reference, &test},
          w,
          h,
          spatial_filters(pixels_per_degree),
          feature_filters(pixels_per_degree),
          0,
          inverse(kRgbToXyz),
          0,
          0,
          0,
          1.0f / std::sqrt(2.0f)};
  s.radius = std::max(s.spatial.radius, s.features.radius);
  const float cmax = max_colour_distance(), pccmax = kPc * cmax;
  // The remapping's two slopes: [0, p_c cmax) onto [0, p_t), the rest onto [p_t, 1].
  s.knee = pccmax;
  s.slope_below = kPt / pccmax;
  s.slope_above = (1.0f - kPt) / (cmax - pccmax);

  FlipResult result;
  result.error = ImageF(w, h, 1);
  // Tiles of 256 columns by 128 rows: the rings fit a core's L2 cache, and
  // the first 2 radius rows each tile filters before its first output row
  // cost a sixth more of the horizontal filtering.
  constexpr int kTileColumns = 256, kTileRows = 128;
  const int columns = (w + kTileColumns - 1) / kTileColumns;
  const int tiles = columns * ((h + kTileRows - 1) / kTileRows);
  tbb::enumerable_thread_specific<Scratch> scratch(std::min(w, kTileColumns), s.radius);
  tbb::parallel_for(
      tbb::blocked_range<int>(0, tiles, 1),
      [&](const tbb::blocked_range<int>& r) {
        Scratch& sc = scratch.local();
        for (int i = r.begin(); i < r.end(); ++i) {
          const int x0 = (i % columns) * kTileColumns, y0 = (i / columns) * kTileRows;
          tile_on(path, s, sc,
                  {y0, std::min(h, y0 + kTileRows), x0, std::min(w, x0 + kTileColumns)},
                  result.error.data.data());
        }
      },
      tbb::simple_partitioner());
  std::vector<double> row_sums(static_cast<std::size_t>(h), 0.0);
  tbb::parallel_for(0, h, [&](int y) {
    const float* row = &result.error.data[static_cast<std::size_t>(y) * w];
    double sum = 0;
    for (int x = 0; x < w; ++x) sum += row[x];
    row_sums[static_cast<std::size_t>(y)] = sum;
  });
  double total = 0;
  for (double v : row_sums) total += v;  // in row order: the same sum on any thread count
  result.mean = total / static_cast<double>(reference.pixel_count());
  return result;
}

FlipResult flip(const ImageF& reference, const ImageF& test, double pixels_per_degree) {
  return detail::flip_on(detail::widest_simd_path(), reference, test, pixels_per_degree);
}

}  // namespace sb::metrics
