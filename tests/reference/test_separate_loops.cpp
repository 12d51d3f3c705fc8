// The union of integer loops without Clipper
// (harness/reference/separate_loops.h), against Clipper's union of the
// same loops: the same area wherever it answers, and an answer only where
// the loops are simple and apart (else Clipper must decide).
#include <gtest/gtest.h>

#include <algorithm>
#include <clipper.hpp>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "reference/separate_loops.h"

namespace {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;
using sb::reference::detail::separate_loops_area;

double clipper_union(const Paths& loops) {
  ClipperLib::Clipper clipper;
  clipper.AddPaths(loops, ClipperLib::ptSubject, true);
  Paths united;
  clipper.Execute(ClipperLib::ctUnion, united, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  double area = 0.0;
  for (const Path& p : united) area += ClipperLib::Area(p);
  return area;
}

// A star-shaped loop around (x, y): corners at increasing angles (a simple
// polygon), counter-clockwise unless `clockwise`.
Path star(std::mt19937& rng, double x, double y, double radius, bool clockwise) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int n = 3 + int(unit(rng) * 40.0);
  std::vector<double> angles(static_cast<size_t>(n));
  for (double& a : angles) a = 2.0 * std::numbers::pi * unit(rng);
  std::sort(angles.begin(), angles.end());
  Path loop;
  for (const double a : angles) {
    const double r = radius * (0.3 + 0.7 * unit(rng));
    const IntPoint q{ClipperLib::cInt(std::llround(x + r * std::cos(a))),
                     ClipperLib::cInt(std::llround(y + r * std::sin(a)))};
    if (loop.empty() || !(loop.back() == q)) loop.push_back(q);
  }
  if (clockwise) std::reverse(loop.begin(), loop.end());
  return loop;
}

TEST(ReferenceSeparateLoops, AnswersAsClipperDoesAndOnlyForLoopsApart) {
  std::mt19937 rng(67);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int answered = 0, declined = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    Paths loops;
    const int count = 1 + int(unit(rng) * 4.0);
    // Far apart or crowded, some wound clockwise, coordinates up to 2^30.
    const double spread = unit(rng) < 0.5 ? 1e9 : 3e8;
    for (int k = 0; k < count; ++k)
      loops.push_back(star(rng, spread * (unit(rng) - 0.5), spread * (unit(rng) - 0.5),
                           1e8 * (0.05 + unit(rng)), unit(rng) < 0.15));
    if (std::any_of(loops.begin(), loops.end(), [](const Path& p) { return p.size() < 3; }))
      continue;
    const std::optional<double> area = separate_loops_area(loops, loops.size());
    const double truth = clipper_union(loops);
    if (area) {
      ++answered;
      EXPECT_NEAR(*area, truth, 1e-12 * std::max(truth, 1.0)) << "trial " << trial;
    } else {
      ++declined;
    }
  }
  EXPECT_GT(answered, 500);
  EXPECT_GT(declined, 500);
}

TEST(ReferenceSeparateLoops, DeclinesLoopsThatTouchCrossNestOrDoubleBack) {
  const Path square{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  const Path right{{20, 0}, {30, 0}, {30, 10}, {20, 10}};
  // Apart: the sum; one loop either way round: its area.
  EXPECT_EQ(separate_loops_area({square, right}, 2), 200.0);
  EXPECT_EQ(separate_loops_area({Path(square.rbegin(), square.rend())}, 1), 100.0);
  // Sharing a corner, or an edge, or overlapping.
  EXPECT_FALSE(separate_loops_area({square, {{10, 10}, {20, 10}, {20, 20}}}, 2));
  EXPECT_FALSE(separate_loops_area({square, {{10, 0}, {20, 0}, {20, 10}, {10, 10}}}, 2));
  EXPECT_FALSE(separate_loops_area({square, {{5, 5}, {15, 5}, {15, 15}, {5, 15}}}, 2));
  // One inside the other, either way round.
  const Path inner{{2, 2}, {8, 2}, {8, 8}, {2, 8}};
  EXPECT_FALSE(separate_loops_area({square, inner}, 2));
  EXPECT_FALSE(separate_loops_area({inner, square}, 2));
  EXPECT_FALSE(separate_loops_area({square, Path(inner.rbegin(), inner.rend())}, 2));
  // A figure of eight (a corner visited twice), a bow tie (crossing
  // itself), an outline doubling back along an edge.
  EXPECT_FALSE(separate_loops_area({{{0, 0}, {10, 0}, {5, 5}, {10, 10}, {0, 10}, {5, 5}}}, 1));
  EXPECT_FALSE(separate_loops_area({{{0, 0}, {10, 10}, {10, 0}, {0, 10}}}, 1));
  EXPECT_FALSE(separate_loops_area({{{0, 0}, {10, 0}, {10, 10}, {10, 5}, {0, 10}}}, 1));
  // Two loops on the same line touching end to end.
  EXPECT_FALSE(separate_loops_area({{{0, 0}, {10, 0}, {5, 5}}, {{10, 0}, {20, 0}, {15, 5}}}, 2));
}

}  // namespace
