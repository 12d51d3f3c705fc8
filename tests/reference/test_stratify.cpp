#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <stdexcept>
#include <vector>

#include "reference/stratify.h"

namespace {

using sb::reference::detail::Layout;
using sb::reference::detail::make_layout;

class LayoutTest : public ::testing::TestWithParam<int> {};

TEST_P(LayoutTest, EqualAreaCellsCoverTheSquareOnce) {
  const int n = GetParam();
  const Layout l = make_layout(n);
  ASSERT_EQ(l.order.size(), size_t(n));
  std::set<uint32_t> cells;
  double area = 0;
  for (const auto& st : l.order) {
    cells.insert(st.cell);
    EXPECT_NEAR(double(st.ds) * st.dt, 1.0 / n, 1e-6 / n);
    EXPECT_GE(st.s0, 0.0f);
    EXPECT_LE(st.s0 + st.ds, 1.0f + 1e-6f);
    EXPECT_LE(st.t0 + st.dt, 1.0f + 1e-6f);
    area += double(st.ds) * st.dt;
  }
  EXPECT_EQ(cells.size(), size_t(n));
  EXPECT_EQ(*cells.rbegin(), uint32_t(n - 1));
  EXPECT_NEAR(area, 1.0, 1e-5);
  // Cells are near-square in (s,t): rows differ by at most one cell.
  for (int r = 0; r < l.rows; ++r) {
    const int count = l.row_start[size_t(r) + 1] - l.row_start[size_t(r)];
    EXPECT_GE(count, 2);
    EXPECT_LE(std::abs(count - n / l.rows), 1);
  }
  // Variance groups partition the cells into pairs and triples.
  ASSERT_GE(l.group_begin.size(), 2u);
  EXPECT_EQ(l.group_begin.front(), 0u);
  EXPECT_EQ(l.group_begin.back(), uint32_t(n));
  for (size_t g = 0; g + 1 < l.group_begin.size(); ++g) {
    const uint32_t size = l.group_begin[g + 1] - l.group_begin[g];
    EXPECT_TRUE(size == 2 || size == 3) << size;
  }
}

INSTANTIATE_TEST_SUITE_P(reference, LayoutTest,
                         ::testing::Values(2, 3, 4, 5, 7, 16, 17, 32, 64, 100, 128, 256, 1000,
                                           1024));

// A segment light's layout (Strata::AlongS or AlongT): N cells of width 1/N
// edge to edge along the one axis, each spanning the other, in order (so a
// packet holds neighbours), paired with the next cell (a triple at the end
// when N is odd).
class SegmentLayoutTest : public ::testing::TestWithParam<int> {};

TEST_P(SegmentLayoutTest, NStrataPartitionTheSegment) {
  using sb::reference::detail::Strata;
  const int n = GetParam();
  for (const Strata along : {Strata::AlongS, Strata::AlongT}) {
    const Layout l = make_layout(n, along);
    ASSERT_EQ(l.order.size(), size_t(n));
    EXPECT_EQ(l.rows, 1);
    double end = 0.0;  // where the previous stratum stopped
    for (size_t i = 0; i < l.order.size(); ++i) {
      const auto& st = l.order[i];
      const bool s_axis = along == Strata::AlongS;
      const double lo = s_axis ? st.s0 : st.t0, width = s_axis ? st.ds : st.dt;
      EXPECT_EQ(st.cell, uint32_t(i));
      EXPECT_NEAR(lo, double(i) / n, 0x1p-24);
      EXPECT_NEAR(width, 1.0 / n, 0x1p-24 / n);
      EXPECT_NEAR(lo, end, 1e-7) << "gap or overlap before stratum " << i;
      end = lo + width;
      // The other axis is not divided: the segment has no extent there.
      EXPECT_EQ(s_axis ? st.t0 : st.s0, 0.0f);
      EXPECT_EQ(s_axis ? st.dt : st.ds, 1.0f);
    }
    EXPECT_NEAR(end, 1.0, 1e-6);
    // Neighbour pairs from the first cell on; an odd N's last group is a
    // triple; one cell (N = 1) has no group.
    ASSERT_FALSE(l.group_begin.empty());
    EXPECT_EQ(l.group_begin.back(), uint32_t(n));
    const size_t groups = l.group_begin.size() - 1;
    EXPECT_EQ(groups, size_t(n / 2));
    for (size_t g = 0; g < groups; ++g) {
      EXPECT_EQ(l.group_begin[g], uint32_t(2 * g));
      const uint32_t size = l.group_begin[g + 1] - l.group_begin[g];
      EXPECT_EQ(size, g + 1 == groups && n % 2 == 1 ? 3u : 2u) << "group " << g;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(reference, SegmentLayoutTest,
                         ::testing::Values(1, 2, 3, 5, 16, 17, 100, 256, 1000, 1024));

TEST(referenceLayout, SquareCountsAreTheJitteredGrid) {
  const Layout l = make_layout(256);
  EXPECT_EQ(l.rows, 16);
  for (const auto& st : l.order) {
    EXPECT_FLOAT_EQ(st.ds, 1.0f / 16);
    EXPECT_FLOAT_EQ(st.dt, 1.0f / 16);
  }
  // The first packet is the 4×4 block in the corner.
  for (int j = 0; j < 16; ++j) {
    EXPECT_LT(l.order[size_t(j)].s0, 0.25f);
    EXPECT_LT(l.order[size_t(j)].t0, 0.25f);
  }
}

TEST(referenceLayout, OneSampleCoversTheWholeLightAndZeroIsRejected) {
  EXPECT_THROW(make_layout(0), std::invalid_argument);
  EXPECT_THROW(make_layout(-1), std::invalid_argument);
  const Layout l = make_layout(1);
  ASSERT_EQ(l.order.size(), 1u);
  EXPECT_EQ(l.order[0].s0, 0.0f);
  EXPECT_EQ(l.order[0].t0, 0.0f);
  EXPECT_EQ(l.order[0].ds, 1.0f);
  EXPECT_EQ(l.order[0].dt, 1.0f);
  // No pair to compare: the largest variance one 0/1 sample can have.
  for (uint8_t v : {uint8_t(0), uint8_t(1)})
    EXPECT_EQ(sb::reference::detail::stratified_variance(&v, l), 0.25);
}

TEST(referenceLayout, VarianceOfPairs) {
  const Layout l = make_layout(16);  // 4×4: 8 pairs
  std::vector<uint8_t> vis(16, 1);
  EXPECT_EQ(sb::reference::detail::stratified_variance(vis.data(), l), 0.0);
  vis[0] = 0;  // one disagreeing pair: 1/N^2
  EXPECT_DOUBLE_EQ(sb::reference::detail::stratified_variance(vis.data(), l), 1.0 / 256);
  vis[1] = 0;  // the pair agrees again
  EXPECT_EQ(sb::reference::detail::stratified_variance(vis.data(), l), 0.0);
}

TEST(referenceSampler, UniformAndDecorrelated) {
  // Mean and u-v correlation over many draws of one key, and keys that differ.
  const uint64_t key = sb::reference::detail::pixel_key(1, 12345, 256);
  EXPECT_NE(key, sb::reference::detail::pixel_key(1, 12346, 256));
  EXPECT_NE(key, sb::reference::detail::pixel_key(2, 12345, 256));
  EXPECT_NE(key, sb::reference::detail::pixel_key(1, 12345, 64));
  double su = 0, sv = 0, suv = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    float u, v;
    sb::reference::detail::sample_uv(key, uint32_t(i), u, v);
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    ASSERT_GE(v, 0.0f);
    ASSERT_LT(v, 1.0f);
    su += u;
    sv += v;
    suv += double(u) * v;
  }
  EXPECT_NEAR(su / n, 0.5, 0.005);
  EXPECT_NEAR(sv / n, 0.5, 0.005);
  EXPECT_NEAR(suv / n - (su / n) * (sv / n), 0.0, 0.003);
}

}  // namespace
