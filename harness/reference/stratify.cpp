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

}  // namespace sb::reference::detail
