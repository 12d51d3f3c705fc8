#include "reference/stratify.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sb::reference::detail {

namespace {

// One row of spp cells along s or t, traced in order: 16 neighbouring cells
// per packet are one short stretch of the segment.
Layout segment_layout(int spp, Strata strata) {
  Layout l;
  l.spp = spp;
  l.rows = 1;
  l.row_start = {0, spp};
  for (int c = 0; c + 1 < spp; c += 2) l.group_begin.push_back(uint32_t(c));
  l.group_begin.push_back(uint32_t(spp));
  for (int c = 0; c < spp; ++c) {
    const float lo = float(double(c) / spp), width = float(1.0 / spp);
    Stratum st{0.0f, 1.0f, 0.0f, 1.0f, uint32_t(c)};
    (strata == Strata::AlongS ? st.s0 : st.t0) = lo;
    (strata == Strata::AlongS ? st.ds : st.dt) = width;
    l.order.push_back(st);
  }
  return l;
}

}  // namespace

Layout make_layout(int spp, Strata strata) {
  if (spp < 1) throw std::invalid_argument("reference: spp must be at least 1");
  if (strata != Strata::Square) return segment_layout(spp, strata);
  Layout l;
  l.spp = spp;
  const int64_t n = spp;
  // At least two cells per row, so every row can hold a pair.
  l.rows = std::max(1, std::min(int(std::lround(std::sqrt(double(spp)))), spp / 2));
  const int64_t k = l.rows;
  for (int64_t r = 0; r <= k; ++r) l.row_start.push_back(int(r * n / k));

  for (int r = 0; r < l.rows; ++r) {
    const int begin = l.row_start[size_t(r)], count = l.row_start[size_t(r) + 1] - begin;
    // Pairs; an odd row's last pair absorbs the left-over cell (a triple).
    for (int c = 0; c + 1 < count; c += 2) l.group_begin.push_back(uint32_t(begin + c));
  }
  l.group_begin.push_back(uint32_t(spp));

  for (int r0 = 0; r0 < l.rows; r0 += 4) {
    const int r1 = std::min(r0 + 4, l.rows);
    int widest = 0;
    for (int r = r0; r < r1; ++r)
      widest = std::max(widest, l.row_start[size_t(r) + 1] - l.row_start[size_t(r)]);
    for (int c0 = 0; c0 < widest; c0 += 4)
      for (int r = r0; r < r1; ++r) {
        const int begin = l.row_start[size_t(r)], count = l.row_start[size_t(r) + 1] - begin;
        for (int c = c0; c < std::min(c0 + 4, count); ++c) {
          Stratum st;
          st.ds = float(1.0 / count);
          st.s0 = float(double(c) / count);
          st.dt = float(double(count) / double(spp));
          st.t0 = float(double(begin) / double(spp));
          st.cell = uint32_t(begin + c);
          l.order.push_back(st);
        }
      }
  }
  return l;
}

double stratified_variance(const uint8_t* visible, const Layout& layout) {
  // One sample has no neighbour to compare with: report the largest variance
  // a 0/1 sample can have (p = 1/2), so a 1-spp reference is never trusted.
  if (layout.spp == 1) return 0.25;
  int64_t sum = 0;  // sum of m(g-m)/(g-1) scaled by 2 to stay integral (g is 2 or 3)
  for (size_t gi = 0; gi + 1 < layout.group_begin.size(); ++gi) {
    const uint32_t b = layout.group_begin[gi], e = layout.group_begin[gi + 1];
    const int64_t g = e - b;
    int64_t m = 0;
    for (uint32_t i = b; i < e; ++i) m += visible[i];
    // |g|/(|g|-1) * sum (f - mean)^2 = m(g-m)/(g-1) for 0/1 values.
    sum += 2 * m * (g - m) / (g - 1);
  }
  const double n = layout.spp;
  return 0.5 * double(sum) / (n * n);
}

namespace {

// Σ m(g − m)/(g − 1) over the groups of one line of `count` cells (`first`,
// `first` + `step`, ...), paired from the line's cell `offset` (0 or 1); a
// cell left over at either end joins the pair next to it (a triple): the
// collapsed-strata sum of that grouping, times N² the variance.
double line_groups(const uint8_t* visible, int first, int step, int count, int offset) {
  if (count < 2) return 0.0;
  // The groups' bounds: 0, then every second cell from offset == 0 ? 2 : 1,
  // then count; a group of one cell at either end joins its neighbour.
  // Walked in place (no list: this runs for every traced pixel).
  int lo = 0;
  int next = offset == 0 ? 2 : 1;
  if (next == 1 && next < count) next = 3;  // the leading single cell joins the first pair
  double sum = 0.0;
  while (lo < count) {
    int hi = next < count ? next : count;
    if (hi < count && count - hi == 1) hi = count;  // the trailing single cell joins the last
    const int size = hi - lo;
    int m = 0;
    for (int i = lo; i < hi; ++i) m += visible[first + i * step];
    sum += double(m) * double(size - m) / double(size - 1);
    lo = hi;
    next = hi + 2;
  }
  return sum;
}

// The collapsed-strata variance over pairs along each row shifted by one
// cell (the layout's own groups start at each row's first cell).
double shifted_rows_variance(const uint8_t* visible, const Layout& layout) {
  double sum = 0.0;
  for (int r = 0; r < layout.rows; ++r) {
    const int begin = layout.row_start[size_t(r)];
    sum += line_groups(visible, begin, 1, layout.row_start[size_t(r) + 1] - begin, 1);
  }
  const double n = layout.spp;
  return sum / (n * n);
}

// The mean of the collapsed-strata variances over pairs down each column,
// from the first row and from the second; 0 unless every row has as many
// cells (a square grid) and there are two rows.
double columns_variance(const uint8_t* visible, const Layout& layout) {
  const int width = layout.row_start[1];
  if (layout.rows < 2 || width * layout.rows != layout.spp) return 0.0;
  double sum = 0.0;
  for (int offset : {0, 1})
    for (int c = 0; c < width; ++c) sum += line_groups(visible, c, width, layout.rows, offset);
  const double n = layout.spp;
  return 0.5 * sum / (n * n);
}

}  // namespace

double standard_error(const uint8_t* visible, const Layout& layout) {
  int64_t reached = 0;
  for (int i = 0; i < layout.spp; ++i) reached += visible[i];
  if (reached == 0 || reached == layout.spp) return 0.0;
  const double rows =
      0.5 * (stratified_variance(visible, layout) + shifted_rows_variance(visible, layout));
  if (rows > 0.0) return std::sqrt(rows);
  if (const double columns = columns_variance(visible, layout); columns > 0.0)
    return std::sqrt(columns);
  const double p = double(reached) / double(layout.spp);
  return std::sqrt(p * (1.0 - p) / double(layout.spp));
}

double stop_bias_bound(int n) {
  const double m = double(n);
  return std::pow(m / (m + 1.0), m) / (m + 1.0);  // p (1 - p)^n at p = 1/(n + 1)
}

double stop_rms_bound(int n) {
  const double h = 0.5 * double(n);
  return std::pow(h / (h + 1.0), h) / (h + 1.0);  // p (1 - p)^(n/2) at p = 1/(n/2 + 1)
}

}  // namespace sb::reference::detail
