#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "results/pareto.h"

namespace sb {

using results::pareto_front;
using results::pareto_front_indices;
using results::ParetoPoint;

namespace {

std::vector<std::string> labels(const std::vector<ParetoPoint>& front) {
  std::vector<std::string> out;
  for (const auto& p : front) out.push_back(p.label);
  return out;
}

TEST(Pareto, EmptyInputGivesEmptyFront) { EXPECT_TRUE(pareto_front({}).empty()); }

TEST(Pareto, SinglePointIsTheFront) {
  EXPECT_EQ(labels(pareto_front({{3.0, 0.2, "only"}})), std::vector<std::string>{"only"});
}

TEST(Pareto, ConstructedSetHasTheKnownFront) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<ParetoPoint> points = {
      {1.0, 0.5, "a"},
      {2.0, 0.3, "b"},
      {2.0, 0.4, "same_time_worse"},    // dominated by b: equal time, more error
      {3.0, 0.3, "same_error_slower"},  // dominated by b: equal error, slower
      {4.0, 0.1, "dup_z"},              // exact duplicates: both on the front,
      {4.0, 0.1, "dup_y"},              // ordered by label
      {5.0, 0.6, "dominated"},
      {0.5, 0.9, "fastest"},
      {nan, 0.0, "nan_time"},  // non-finite: excluded, although it would dominate
      {6.0, inf, "inf_error"},
      {inf, 0.01, "inf_time"},
      {-inf, 0.0, "minus_inf_time"},
      {7.0, 0.05, "slow_best"},
      {8.0, 0.05, "slower_equal"},  // dominated by slow_best
  };
  const std::vector<std::string> expected = {"fastest", "a", "b", "dup_y", "dup_z", "slow_best"};
  EXPECT_EQ(labels(pareto_front(points)), expected);
  EXPECT_EQ(pareto_front_indices(points), (std::vector<std::size_t>{7, 0, 1, 5, 4, 12}));

  // The same front whatever the input order.
  std::vector<ParetoPoint> shuffled = points;
  std::mt19937 rng(7);
  for (int i = 0; i < 20; ++i) {
    std::shuffle(shuffled.begin(), shuffled.end(), rng);
    EXPECT_EQ(labels(pareto_front(shuffled)), expected);
  }
}

TEST(Pareto, EqualTimesKeepOnlyTheLowestError) {
  const std::vector<ParetoPoint> points = {
      {1.0, 0.3, "c"}, {1.0, 0.1, "b"}, {1.0, 0.2, "d"}, {1.0, 0.1, "a"}};
  EXPECT_EQ(labels(pareto_front(points)), (std::vector<std::string>{"a", "b"}));
}

TEST(Pareto, AllNonFiniteGivesEmptyFront) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(pareto_front({{nan, 1.0, "x"}, {1.0, nan, "y"}}).empty());
}

// Against the definition, on random points with many ties.
TEST(Pareto, MatchesBruteForceOnRandomPoints) {
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> coord(0, 9);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<ParetoPoint> points;
    for (int i = 0; i < 25; ++i)
      points.push_back({double(coord(rng)), double(coord(rng)) / 10.0, std::to_string(i)});
    const auto front = pareto_front_indices(points);
    for (std::size_t i = 0; i < points.size(); ++i) {
      bool dominated = false;
      for (const auto& q : points) {
        const auto& p = points[i];
        dominated |=
            q.time <= p.time && q.error <= p.error && (q.time < p.time || q.error < p.error);
      }
      const bool on_front = std::find(front.begin(), front.end(), i) != front.end();
      EXPECT_EQ(on_front, !dominated) << "trial " << trial << " point " << i;
    }
    for (std::size_t k = 1; k < front.size(); ++k) {
      const auto& a = points[front[k - 1]];
      const auto& b = points[front[k]];
      const bool duplicate = a.time == b.time && a.error == b.error;
      EXPECT_TRUE(duplicate || (a.time < b.time && a.error > b.error));
    }
  }
}

}  // namespace
}  // namespace sb
