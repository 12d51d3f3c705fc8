#include "metrics/flip_tile.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "metrics/flip_colour.h"
#include "metrics/flip_math.h"

namespace sb::metrics::flip_detail {

using core::ImageF;

static_assert(kQf == 0.5f, "the feature difference is taken as a square root below");

namespace {

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

// Whether a tile filters side 0 (the reference) or 1 (the test).
inline bool filters(const Setup& s, int side) {
  return side == 0 ? s.sides != Sides::TestOnly : s.sides != Sides::ReferenceOnly;
}

// FLIP of output row y from the rings: the vertical filters, each side's
// Hunt L*a*b* and feature magnitudes, then the colour and feature
// differences (under ReferenceOnly, the reference's values into the
// prepared planes instead).
template <int Lanes>
[[gnu::always_inline]] inline void flip_row(const Setup& s, Scratch& sc, int y, int first, int x0,
                                            int w, float* out) {
  for (int side = 0; side < 2; ++side) {
    if (!filters(s, side)) continue;
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
    if (!filters(s, side)) continue;
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
  // The reference's values: its lines, or its prepared planes' row.
  std::array<const float*, kPreparedPlanes> r{};
  const std::size_t plane = static_cast<std::size_t>(s.width) * s.height;
  const std::size_t at = static_cast<std::size_t>(y) * s.width + x0;
  for (int k = 0; k < kPreparedPlanes; ++k) {
    // Lines 0, 1, 2 hold L*a*b*, 4 and 5 the magnitudes.
    const int line = k < kEdge ? k : k + 1;
    const float* own = sc.line(0) + static_cast<std::size_t>(line) * w;
    if (s.sides == Sides::ReferenceOnly)
      std::memcpy(s.prepared_out + k * plane + at, own,
                  static_cast<std::size_t>(w) * sizeof(float));
    r[k] = s.sides == Sides::TestOnly ? s.prepared_in + k * plane + at : own;
  }
  if (s.sides == Sides::ReferenceOnly) return;
  const float* t = sc.line(8);
  float* colour = sc.line(6);  // the reference's dy, no longer needed
  // Locals, not references: a choice between values in registers is a
  // select, one between loads is a branch.
  const float knee = s.knee, slope_below = s.slope_below, slope_above = s.slope_above;
  const float feature_norm = s.feature_norm;
  const float *rl = r[kL], *ra = r[kA], *rb = r[kB], *redge = r[kEdge], *rpoint = r[kPoint];
  for (int x = 0; x < w; ++x) {
    const float dl = rl[x] - t[x], da = ra[x] - t[w + x], db = rb[x] - t[2 * w + x];
    const float c = fast_pow(std::abs(dl) + std::sqrt(da * da + db * db), kQc);
    colour[x] = c < knee ? c * slope_below : kPt + (c - knee) * slope_above;
  }
  for (int x = 0; x < w; ++x) {
    // q_f = 0.5: the square root.
    const float edge = std::abs(redge[x] - t[4 * w + x]);
    const float point = std::abs(rpoint[x] - t[5 * w + x]);
    const float feature = std::sqrt(feature_norm * (edge > point ? edge : point));
    out[x] = fast_pow(colour[x], 1.0f - feature);
  }
}

// Tile row v (an image row, or beyond the image its edge row) of both
// images into the rings.
template <int Lanes>
[[gnu::always_inline]] inline void enter_rows(const Setup& s, Scratch& sc, const Tile& t, int v,
                                              int first) {
  const int row = std::clamp(v, 0, s.height - 1), slot = (v - first) % sc.slots();
  for (int side = 0; side < 2; ++side)
    if (filters(s, side)) enter_row<Lanes>(s, sc, side, row, slot, t.x0, t.x1);
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
    flip_row<Lanes>(s, sc, y, first, t.x0, t.x1 - t.x0,
                    error ? error + static_cast<std::size_t>(y) * s.width + t.x0 : nullptr);
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

}  // namespace

void tile_on(detail::SimdPath path, const Setup& s, Scratch& sc, const Tile& t, float* error) {
#if defined(__x86_64__)
  if (path == detail::SimdPath::Avx512) return tile_avx512(s, sc, t, error);
  if (path == detail::SimdPath::Avx2) return tile_avx2(s, sc, t, error);
#endif
  (void)path;  // elsewhere every path is the baseline
  tile_baseline(s, sc, t, error);
}

}  // namespace sb::metrics::flip_detail
