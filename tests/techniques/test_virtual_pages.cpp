// virtual_shadow_map's CPU side (techniques/cascaded/virtual_pages.h): the
// clipmap's levels (each twice the one before, the coarsest over the view,
// centres on whole pages) and the page allocation with its overflow rule
// (the coarsest level first, then nearest first; the rest dropped and
// counted), against answers worked out by hand. No GL.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "cascaded/cascade_fit.h"
#include "cascaded/virtual_pages.h"

namespace sb::test {
namespace {

using techniques::cascaded::allocate_pages;
using techniques::cascaded::box_corners;
using techniques::cascaded::Clipmap;
using techniques::cascaded::kDroppedPage;
using techniques::cascaded::kNoPage;
using techniques::cascaded::kUnmarked;
using techniques::cascaded::PageAllocation;
using techniques::cascaded::plan_clipmap;

std::uint32_t bits(float d) { return std::bit_cast<std::uint32_t>(d); }

Clipmap a_clipmap(const glm::vec3& eye, int levels) {
  const auto corners = box_corners({-50.0f, 0.0f, -50.0f}, {50.0f, 10.0f, 50.0f});
  return plan_clipmap(eye, 70.0f, 0.001f, glm::normalize(glm::vec3(-1.0f, -2.0f, -0.5f)), corners,
                      corners, 4096, 128, levels);
}

TEST(VirtualClipmap, EachLevelDoublesAndTheCoarsestCoversTheViewOnWholePages) {
  const Clipmap c = a_clipmap({3.3f, 1.7f, 12.1f}, 5);
  ASSERT_EQ(c.levels.size(), 5u);
  // Half extent: 70 and 70·0.001·4096/2 = 143.4 → 256 (a power of two).
  EXPECT_FLOAT_EQ(c.levels[4].texel * 4096.0f, 512.0f);
  for (int l = 0; l + 1 < 5; ++l) {
    EXPECT_FLOAT_EQ(c.levels[size_t(l) + 1].texel, 2.0f * c.levels[size_t(l)].texel);
    const float page = 128.0f * c.levels[size_t(l)].texel;
    // The centre (lo + half) lies on the page grid of the level.
    const glm::vec2 centre = c.levels[size_t(l)].lo + 2048.0f * c.levels[size_t(l)].texel;
    EXPECT_NEAR(centre.x / page, std::round(centre.x / page), 1e-3);
    EXPECT_NEAR(centre.y / page, std::round(centre.y / page), 1e-3);
    // And within half a page of the eye.
    const glm::vec2 e = glm::vec2(c.view * glm::vec4(c.eye, 1.0f));
    EXPECT_LE(std::abs(centre.x - e.x), 0.5f * page + 1e-3f);
    EXPECT_LE(std::abs(centre.y - e.y), 0.5f * page + 1e-3f);
  }
}

TEST(VirtualClipmap, AWorldPointKeepsItsTexelWhileTheCameraMovesWithinAPage) {
  const Clipmap a = a_clipmap({3.30f, 1.7f, 12.10f}, 4);
  const Clipmap b = a_clipmap({3.31f, 1.7f, 12.12f}, 4);
  for (int l = 0; l < 4; ++l) {
    const glm::vec2 d = b.levels[size_t(l)].lo - a.levels[size_t(l)].lo;
    const float page = 128.0f * a.levels[size_t(l)].texel;
    // Either unmoved or moved by whole pages: never by a fraction of a texel.
    EXPECT_NEAR(d.x / page, std::round(d.x / page), 1e-3) << l;
    EXPECT_NEAR(d.y / page, std::round(d.y / page), 1e-3) << l;
  }
}

// 2 levels of 2×2 pages: pages 0-3 the fine level, 4-7 the coarsest.
TEST(PageAllocation, EveryMarkedPageGetsASlotWhenThePoolHoldsThem) {
  std::vector<std::uint32_t> marks(8, kUnmarked);
  marks[0] = bits(3.0f);
  marks[1] = bits(1.0f);
  marks[3] = bits(2.0f);
  marks[6] = bits(9.0f);
  const PageAllocation a = allocate_pages(marks, 2, 2, 2);
  EXPECT_EQ(a.marked, 4);
  EXPECT_EQ(a.allocated, 4);
  EXPECT_EQ(a.dropped, 0);
  EXPECT_EQ(a.table, (std::vector<int>{0, 1, kNoPage, 2, kNoPage, kNoPage, 3, kNoPage}));
  // Pages 0 and 1 are neighbours in a row and in the pool: one run.
  ASSERT_EQ(a.runs.size(), 3u);
  EXPECT_EQ(a.runs[0].count, 2);
  EXPECT_EQ(a.runs[0].col0, 0);
  EXPECT_EQ(a.runs[1].row, 1);
  EXPECT_EQ(a.runs[2].level, 1);
}

TEST(PageAllocation, OnOverflowKeepsTheCoarsestLevelThenTheNearestAndCountsTheDropped) {
  std::vector<std::uint32_t> marks(8, kUnmarked);
  marks[0] = bits(3.0f);
  marks[1] = bits(1.0f);
  marks[2] = bits(0.5f);
  marks[3] = bits(2.0f);
  marks[5] = bits(9.0f);  // the coarsest level: kept although the farthest
  // A pool of 2×2 = 4 slots for 5 marked pages.
  const PageAllocation a = allocate_pages(marks, 2, 2, 2);
  EXPECT_EQ(a.marked, 5);
  EXPECT_EQ(a.allocated, 4);
  EXPECT_EQ(a.dropped, 1);
  // Kept: page 5, then 2 (0.5), 1 (1.0), 3 (2.0); dropped: page 0 (3.0).
  // Slots in page order: 1 → 0, 2 → 1, 3 → 2, 5 → 3.
  EXPECT_EQ(a.table, (std::vector<int>{kDroppedPage, 0, 1, 2, kNoPage, 3, kNoPage, kNoPage}));
  // Runs never wrap a pool row: slots 0-1 are pool row 0, slot 2 row 1.
  for (const auto& r : a.runs) EXPECT_LE(r.slot0 % 2 + r.count, 2);
}

}  // namespace
}  // namespace sb::test
