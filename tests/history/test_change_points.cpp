// The change-point detector of the performance history, tested
// against the steps the synthetic series were built with: seeded lognormal
// noise around known levels (value = level * exp(noise * z), z ~ N(0, 1)),
// and, for PELT alone, an exhaustive search over every segmentation.
//
// Measured with these seeds (defaults: beta 7, min_segment 3; the same
// figures are in harness/history/change_points.h):
//   - any step reported in noise-only series of 20 runs, 500 series each:
//     1 % noise 0/500, 3 % noise 1/500, 10 % noise 0/500;
//   - a +20 % step after 3 runs, series of 10 to 20 runs, 200 series each:
//     found at run 3 (and no other step): 2 % noise 199/200, 3 % noise 198/200;
//   - a +30 % step at each allowed run of 20 runs (3 to 17), 3 % noise:
//     199/200 at the right run and no other.
// Over 5000 series per case instead (other seeds): false steps 0 %, 0.16 %,
// 0.28 %; +20 % after 3 runs found 100 % (2 %) and 98.0 % (3 %); +30 % alone
// 99.9 %.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "history/change_points.h"

namespace {

using sb::history::ChangePoint;
using sb::history::ChangePointOptions;
using sb::history::find_change_points;
using sb::history::noise_sigma;
using sb::history::pelt_mean_shift;
using sb::history::Scale;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A series of n runs: `level` before run `at`, level * (1 + step) from it on,
// each run times exp(noise * z).
std::vector<double> stepped_series(std::mt19937_64& rng, size_t n, double noise, size_t at,
                                   double step, double level = 1.0) {
  std::normal_distribution<double> z(0.0, 1.0);
  std::vector<double> v(n);
  for (size_t i = 0; i < n; ++i)
    v[i] = (i >= at ? level * (1 + step) : level) * std::exp(noise * z(rng));
  return v;
}

std::vector<size_t> indices(const std::vector<ChangePoint>& cps) {
  std::vector<size_t> out;
  out.reserve(cps.size());
  for (const ChangePoint& c : cps) out.push_back(c.index);
  return out;
}

// How many of `count` noise-only series of `n` runs report any step.
int series_with_a_false_step(uint64_t seed, double noise, size_t n, int count) {
  std::mt19937_64 rng(seed);
  int with_step = 0;
  for (int k = 0; k < count; ++k)
    if (!find_change_points(stepped_series(rng, n, noise, n, 0.0)).empty()) ++with_step;
  return with_step;
}

TEST(ChangePoints, ConstantSeriesHasNoStep) {
  EXPECT_TRUE(find_change_points(std::vector<double>(20, 1.25)).empty());
  ChangePointOptions absolute;
  absolute.scale = Scale::kAbsolute;
  EXPECT_TRUE(find_change_points(std::vector<double>(20, 0.0), absolute).empty());
  EXPECT_TRUE(find_change_points(std::vector<double>(20, 3.5), absolute).empty());
}

TEST(ChangePoints, NoisySeriesWithoutChangeHasNoStep) {
  std::mt19937_64 rng(1);
  for (double noise : {0.005, 0.02, 0.05})
    EXPECT_TRUE(find_change_points(stepped_series(rng, 30, noise, 30, 0.0)).empty()) << noise;
}

TEST(ChangePoints, NoiseOnlySeriesReportAStepInAtMostOnePercent) {
  // 500 series of 20 runs at each noise level; measured 0, 1 and 0.
  EXPECT_LE(series_with_a_false_step(101, 0.01, 20, 500), 5);
  EXPECT_LE(series_with_a_false_step(103, 0.03, 20, 500), 5);
  EXPECT_LE(series_with_a_false_step(110, 0.10, 20, 500), 5);
}

TEST(ChangePoints, TwentyPercentStepAfterThreeRunsIsFoundAtItsRunIn95PercentOfSeries) {
  for (double noise : {0.02, 0.03}) {
    std::mt19937_64 rng(noise < 0.025 ? 202 : 203);
    int found = 0;
    for (int k = 0; k < 200; ++k) {
      const size_t n = 10 + static_cast<size_t>(k) % 11;  // 10 to 20 runs
      const std::vector<size_t> at =
          indices(find_change_points(stepped_series(rng, n, noise, 3, 0.2)));
      if (std::find(at.begin(), at.end(), size_t{3}) != at.end()) ++found;
    }
    EXPECT_GE(found, 190) << noise;  // measured 199 (2 %), 198 (3 %)
  }
}

TEST(ChangePoints, ThirtyPercentStepIsFoundAtItsRunAndNoOther) {
  // What the detector was built to do: every allowed position in 20 runs, 3 % noise.
  std::mt19937_64 rng(303);
  int exact = 0;
  for (int k = 0; k < 200; ++k) {
    const size_t at = 3 + static_cast<size_t>(k) % 15;  // 3 .. 17
    const std::vector<ChangePoint> c = find_change_points(stepped_series(rng, 20, 0.03, at, 0.3));
    if (c.size() == 1 && c[0].index == at) ++exact;
  }
  EXPECT_GE(exact, 198);  // measured 199
}

TEST(ChangePoints, ReportsSegmentMediansRelativeChangeAndStepOverSigma) {
  std::vector<double> v(12, 10.0);
  for (size_t i = 6; i < 12; ++i) v[i] = 13.0;
  v[1] = 10.1;  // medians stay 10 and 13
  v[8] = 12.9;
  const std::vector<ChangePoint> c = find_change_points(v);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].index, 6u);
  EXPECT_DOUBLE_EQ(c[0].before, 10.0);
  EXPECT_DOUBLE_EQ(c[0].after, 13.0);
  EXPECT_NEAR(c[0].relative_change, 0.3, 1e-12);
  EXPECT_EQ(c[0].runs_before, 6u);
  EXPECT_EQ(c[0].runs_after, 6u);
  // sigma is the 0.5 % floor here (MAD of differences is 0): log(1.3) / 0.005.
  EXPECT_NEAR(c[0].step_over_sigma, std::log(1.3) / 0.005, 1e-6);
}

TEST(ChangePoints, UpThenDownStepsAreBothFound) {
  std::mt19937_64 rng(404);
  std::vector<double> v = stepped_series(rng, 24, 0.02, 8, 0.25);
  for (size_t i = 16; i < v.size(); ++i) v[i] /= 1.25 * 1.1;  // back down, 10 % below the start
  const std::vector<ChangePoint> c = find_change_points(v);
  ASSERT_EQ(indices(c), (std::vector<size_t>{8, 16}));
  EXPECT_GT(c[0].relative_change, 0.15);
  EXPECT_LT(c[1].relative_change, -0.2);
}

TEST(ChangePoints, StepAtFirstAndLastAllowedPositionIsFound) {
  const ChangePointOptions options;  // min_segment 3: runs 3 and n - 3
  std::mt19937_64 rng(505);
  for (size_t at : {size_t{3}, size_t{12}})
    EXPECT_EQ(indices(find_change_points(stepped_series(rng, 15, 0.02, at, 0.3))),
              std::vector<size_t>{at});
}

TEST(ChangePoints, SeriesShorterThanTwoMinimumSegmentsHasNoStep) {
  EXPECT_TRUE(find_change_points(std::vector<double>{1, 1, 2, 2, 2}).empty());
  EXPECT_EQ(indices(find_change_points(std::vector<double>{1, 1, 1, 2, 2, 2})),
            std::vector<size_t>{3});
  ChangePointOptions two;
  two.min_segment = 2;
  EXPECT_TRUE(find_change_points(std::vector<double>{1, 2, 2}, two).empty());
  EXPECT_TRUE(find_change_points(std::vector<double>{}).empty());
}

TEST(ChangePoints, NaNGapsAreSkippedAndIndicesStayTheInputs) {
  // Runs 0..9 with a step at run 6; runs 2, 5 and 7 have no value.
  const std::vector<double> v{1.0, 1.01, kNaN, 0.99, 1.0, kNaN, 1.5, kNaN, 1.49, 1.51, 1.5};
  const std::vector<ChangePoint> c = find_change_points(v);
  ASSERT_EQ(indices(c), std::vector<size_t>{6});
  EXPECT_EQ(c[0].runs_before, 4u);  // values, not runs: NaN runs do not count
  EXPECT_EQ(c[0].runs_after, 4u);
  // Three values after the gap are a segment, two are not.
  EXPECT_TRUE(find_change_points(std::vector<double>{1, 1, 1, kNaN, kNaN, 2, 2}).empty());
}

TEST(ChangePoints, AbsoluteScaleFindsASeriesLeavingZero) {
  ChangePointOptions absolute;
  absolute.scale = Scale::kAbsolute;
  const std::vector<double> v{0, 0, 0, 0, 0, 0, 0.02, 0.021, 0.019, 0.02, 0.02};
  const std::vector<ChangePoint> c = find_change_points(v, absolute);
  ASSERT_EQ(indices(c), std::vector<size_t>{6});
  EXPECT_EQ(c[0].before, 0.0);
  EXPECT_DOUBLE_EQ(c[0].after, 0.02);
  EXPECT_TRUE(std::isinf(c[0].relative_change) && c[0].relative_change > 0);
  // A step smaller than min_absolute_change is not reported.
  absolute.min_absolute_change = 0.05;
  EXPECT_TRUE(find_change_points(v, absolute).empty());
  // The relative scale cannot take a zero.
  EXPECT_THROW(find_change_points(v), std::invalid_argument);
}

TEST(ChangePoints, SingleOutlierRunIsNoStep) {
  std::mt19937_64 rng(606);
  for (size_t spike : {size_t{0}, size_t{5}, size_t{10}, size_t{18}, size_t{19}}) {
    std::vector<double> v = stepped_series(rng, 20, 0.02, 20, 0.0);
    v[spike] *= 1.6;
    EXPECT_TRUE(find_change_points(v).empty()) << spike;
    ChangePointOptions two;
    two.min_segment = 2;
    EXPECT_TRUE(find_change_points(v, two).empty()) << spike;
  }
}

TEST(ChangePoints, TwoRunExcursionIsNoStepWithSegmentsOfThreeAndTwoStepsWithTwo) {
  std::vector<double> v(20, 1.0);
  for (size_t i = 0; i < v.size(); ++i) v[i] += 0.01 * static_cast<double>(i % 3);  // 1 % wiggle
  v[10] *= 1.6;
  v[11] *= 1.6;
  EXPECT_TRUE(find_change_points(v).empty());
  ChangePointOptions two;
  two.min_segment = 2;
  EXPECT_EQ(indices(find_change_points(v, two)), (std::vector<size_t>{10, 12}));
}

TEST(ChangePoints, StepIsFoundAtItsRunDespiteAnOutlierRunBeforeIt) {
  std::mt19937_64 rng(607);
  for (size_t spike : {size_t{3}, size_t{5}, size_t{7}}) {
    std::vector<double> v = stepped_series(rng, 20, 0.02, 10, 0.2);
    v[spike] *= 1.6;
    EXPECT_EQ(indices(find_change_points(v)), std::vector<size_t>{10}) << spike;
  }
}

TEST(ChangePoints, ChangeBelowTheMinimumEffectIsNotReported) {
  std::vector<double> v(20, 1.0);
  for (size_t i = 10; i < 20; ++i) v[i] = 1.03;  // +3 %, far above the 0.5 % floor
  EXPECT_TRUE(find_change_points(v).empty());
  ChangePointOptions one_percent;
  one_percent.min_relative_change = 0.01;
  EXPECT_EQ(indices(find_change_points(v, one_percent)), std::vector<size_t>{10});
}

TEST(ChangePoints, RelativeScaleFindsTheSameStepsAtAnyLevel) {
  std::mt19937_64 rng(707);
  const std::vector<double> v = stepped_series(rng, 18, 0.03, 7, 0.25);
  std::vector<double> scaled(v);
  for (double& x : scaled) x *= 1000.0;
  EXPECT_EQ(indices(find_change_points(v)), std::vector<size_t>{7});
  EXPECT_EQ(indices(find_change_points(scaled)), std::vector<size_t>{7});
}

TEST(ChangePoints, RejectsInfiniteValuesNonPositiveRelativeValuesAndBadOptions) {
  EXPECT_THROW(find_change_points(std::vector<double>{1, 2, INFINITY}), std::invalid_argument);
  EXPECT_THROW(find_change_points(std::vector<double>{1, -2, 3}), std::invalid_argument);
  ChangePointOptions bad;
  bad.min_segment = 0;
  EXPECT_THROW(find_change_points(std::vector<double>{1, 2}, bad), std::invalid_argument);
  bad = {};
  bad.beta = 0;
  EXPECT_THROW(find_change_points(std::vector<double>{1, 2}, bad), std::invalid_argument);
}

TEST(ChangePoints, NoiseSigmaRecoversTheNoiseOfALongSeriesWithSteps) {
  std::mt19937_64 rng(808);
  std::normal_distribution<double> z(0.0, 1.0);
  std::vector<double> v(4000);
  for (size_t i = 0; i < v.size(); ++i) v[i] = (i / 500 % 2 == 0 ? 0.0 : 1.0) + 0.1 * z(rng);
  EXPECT_NEAR(noise_sigma(v), 0.1, 0.005);  // 7 steps of 10 sigma do not matter
}

// The least penalised cost over every segmentation with segments of at
// least m values, by trying every set of split points (n <= 14).
double exhaustive_best_cost(const std::vector<double>& y, double penalty, size_t m) {
  const size_t n = y.size();
  auto sse = [&](size_t a, size_t b) {
    double mean = 0;
    for (size_t i = a; i < b; ++i) mean += y[i];
    mean /= static_cast<double>(b - a);
    double s = 0;
    for (size_t i = a; i < b; ++i) s += (y[i] - mean) * (y[i] - mean);
    return s;
  };
  double best = std::numeric_limits<double>::infinity();
  if (n == 0) return 0;
  const uint32_t segmentations = 1u << (n - 1);
  for (uint32_t mask = 0; mask < segmentations; ++mask) {  // bit i-1: a split before i
    double total = 0;
    size_t start = 0;
    bool ok = true;
    for (size_t i = 1; i <= n && ok; ++i) {
      if (i < n && !(mask >> (i - 1) & 1u)) continue;
      if (i - start < m) ok = false;
      total += sse(start, i) + (i < n ? penalty : 0.0);
      start = i;
    }
    if (ok) best = std::min(best, total);
  }
  return best;
}

double cost_of(const std::vector<double>& y, const std::vector<size_t>& splits, double penalty) {
  std::vector<size_t> bounds{0};
  bounds.insert(bounds.end(), splits.begin(), splits.end());
  bounds.push_back(y.size());
  double total = penalty * static_cast<double>(splits.size());
  for (size_t k = 0; k + 1 < bounds.size(); ++k) {
    double mean = 0;
    for (size_t i = bounds[k]; i < bounds[k + 1]; ++i) mean += y[i];
    mean /= static_cast<double>(bounds[k + 1] - bounds[k]);
    for (size_t i = bounds[k]; i < bounds[k + 1]; ++i) total += (y[i] - mean) * (y[i] - mean);
  }
  return total;
}

TEST(ChangePoints, PeltFindsTheOptimumOfAnExhaustiveSearch) {
  std::mt19937_64 rng(909);
  std::normal_distribution<double> z(0.0, 1.0);
  std::uniform_int_distribution<int> level(0, 3);
  for (int k = 0; k < 60; ++k) {
    const size_t n = 6 + static_cast<size_t>(k) % 9;  // 6 to 14
    const size_t m = 1 + static_cast<size_t>(k) % 3;
    const double penalty = 0.5 + static_cast<double>(k % 5);
    std::vector<double> y(n);
    double mean = 0;
    for (size_t i = 0; i < n; ++i) {
      if (i % 4 == 0) mean = level(rng);
      y[i] = mean + 0.4 * z(rng);
    }
    const std::vector<size_t> splits = pelt_mean_shift(y, penalty, m);
    for (size_t i = 0; i < splits.size(); ++i)
      EXPECT_GE(splits[i] - (i == 0 ? 0 : splits[i - 1]), m);
    if (!splits.empty()) {
      EXPECT_GE(n - splits.back(), m);
    }
    EXPECT_NEAR(cost_of(y, splits, penalty), exhaustive_best_cost(y, penalty, m), 1e-9)
        << "series " << k << " n " << n << " m " << m;
  }
}

}  // namespace

namespace {

// The weighted cost (pelt_mean_shift's, with weights) of values [a, b).
double weighted_sse(const std::vector<double>& y, const std::vector<double>& w, size_t a,
                    size_t b) {
  double sw = 0, swy = 0;
  for (size_t i = a; i < b; ++i) {
    sw += w[i];
    swy += w[i] * y[i];
  }
  const double mean = swy / sw;
  double s = 0;
  for (size_t i = a; i < b; ++i) s += w[i] * (y[i] - mean) * (y[i] - mean);
  return s;
}

// Steady runs count 1 toward the minimum segment, loaded ones (w < 0.5) 1/2.
bool long_enough(const std::vector<double>& w, size_t a, size_t b, size_t m) {
  double runs = 0;
  for (size_t i = a; i < b; ++i) runs += w[i] < 0.5 ? 0.5 : 1.0;
  return runs >= static_cast<double>(m);
}

// The least penalised weighted cost and its splits, over every segmentation
// whose segments are long enough.
std::pair<double, std::vector<size_t>> exhaustive_weighted(const std::vector<double>& y,
                                                           const std::vector<double>& w,
                                                           double penalty, size_t m) {
  const size_t n = y.size();
  double best = std::numeric_limits<double>::infinity();
  std::vector<size_t> best_splits;
  if (n == 0) return {best, best_splits};
  for (uint32_t mask = 0; mask < (1u << (n - 1)); ++mask) {
    double total = 0;
    size_t start = 0;
    bool ok = true;
    std::vector<size_t> splits;
    for (size_t i = 1; i <= n && ok; ++i) {
      if (i < n && !(mask >> (i - 1) & 1u)) continue;
      if (!long_enough(w, start, i, m)) ok = false;
      total += weighted_sse(y, w, start, i) + (i < n ? penalty : 0.0);
      if (i < n) splits.push_back(i);
      start = i;
    }
    if (ok && total < best) {
      best = total;
      best_splits = splits;
    }
  }
  return {best, best_splits};
}

}  // namespace

TEST(ChangePoints, WeightedPeltWithLoadedRunsFindsTheOptimumOfAnExhaustiveSearch) {
  std::mt19937_64 rng(910);
  std::normal_distribution<double> z(0.0, 1.0);
  std::uniform_int_distribution<int> level(0, 3);
  std::uniform_real_distribution<double> weight(0.05, 1.0);
  for (int k = 0; k < 80; ++k) {
    const size_t n = 6 + static_cast<size_t>(k) % 9;  // 6 to 14
    const size_t m = 1 + static_cast<size_t>(k) % 3;
    const double penalty = 0.5 + static_cast<double>(k % 5);
    std::vector<double> y(n), w(n);
    double mean = 0;
    for (size_t i = 0; i < n; ++i) {
      if (i % 4 == 0) mean = level(rng);
      y[i] = mean + 0.4 * z(rng);
      w[i] = weight(rng);  // about half of them loaded
    }
    const auto [best, best_splits] = exhaustive_weighted(y, w, penalty, m);
    const std::vector<size_t> splits = pelt_mean_shift(y, w, penalty, m);
    std::vector<size_t> bounds{0};
    bounds.insert(bounds.end(), splits.begin(), splits.end());
    bounds.push_back(n);
    double total = penalty * static_cast<double>(splits.size());
    for (size_t s = 0; s + 1 < bounds.size(); ++s) {
      EXPECT_TRUE(long_enough(w, bounds[s], bounds[s + 1], m)) << "series " << k;
      total += weighted_sse(y, w, bounds[s], bounds[s + 1]);
    }
    if (std::isinf(best)) {
      EXPECT_TRUE(splits.empty()) << "series " << k;  // not even one segment is long enough
    } else {
      EXPECT_NEAR(total, best, 1e-9) << "series " << k << " n " << n << " m " << m;
    }
  }
}

// Runs' own noise: a steady run's median has a standard error of about
// `steady`; a run beside a busy machine, `busy`.
std::vector<double> own_noise(size_t n, double steady, const std::vector<size_t>& busy_runs,
                              double busy) {
  std::vector<double> own(n, steady);
  for (size_t i : busy_runs) own[i] = busy;
  return own;
}

// The case that broke CI: three neighbouring runs on a busy machine, their
// time 18 % off, at the end of the history and in its middle. Without the
// runs' own noise, that is a level (a step); with it, those runs say they
// were loaded, weigh less, and count as half a run each toward the three a
// segment needs, so they make no segment alone.
TEST(ChangePoints, ABusySpellOfThreeRunsIsNoStepWhenTheRunsSayTheyWereLoaded) {
  std::mt19937_64 rng(1001);
  int before = 0, after = 0;
  constexpr int kSeries = 200;
  for (int k = 0; k < kSeries; ++k) {
    const size_t n = 10 + static_cast<size_t>(k) % 11;   // 10 to 20 runs
    const size_t from = k % 2 == 0 ? n - 3 : n / 2 - 1;  // at the end, or in the middle
    std::vector<double> v = stepped_series(rng, n, 0.02, n, 0.0);
    for (size_t i = from; i < from + 3; ++i) v[i] *= k % 4 < 2 ? 1.18 : 1 / 1.18;
    ChangePointOptions as_it_was;
    as_it_was.serial_correlation = false;
    before += find_change_points(v, as_it_was).empty() ? 0 : 1;
    after +=
        find_change_points(v, own_noise(n, 0.01, {from, from + 1, from + 2}, 0.06)).empty() ? 0 : 1;
  }
  // Measured: 200 of 200 with a step before, none after.
  EXPECT_GT(before, kSeries * 9 / 10);
  EXPECT_EQ(after, 0);
}

TEST(ChangePoints, AStepIsFoundOnceEnoughSteadyRunsFollowItsLoadedOnes) {
  // A +25 % step at run 10 of 2 % noise; its first three runs were loaded.
  std::mt19937_64 rng(1002);
  for (int k = 0; k < 50; ++k) {
    const std::vector<double> v = stepped_series(rng, 16, 0.02, 10, 0.25);
    // Three loaded runs count as 1.5: run 13 makes the new level 3 + 1.5 runs long.
    const std::vector<double> thirteen(v.begin(), v.begin() + 13);
    EXPECT_TRUE(find_change_points(thirteen, own_noise(13, 0.01, {10, 11, 12}, 0.06)).empty()) << k;
    const std::vector<double> fifteen(v.begin(), v.begin() + 15);
    EXPECT_EQ(indices(find_change_points(fifteen, own_noise(15, 0.01, {10, 11, 12}, 0.06))),
              std::vector<size_t>{10})
        << k;
  }
}

TEST(ChangePoints, RunsOfTypicalOwnNoiseFindWhatTheValuesAloneFind) {
  std::mt19937_64 rng(1003);
  for (int k = 0; k < 100; ++k) {
    const std::vector<double> v =
        stepped_series(rng, 20, 0.03, 3 + static_cast<size_t>(k) % 14, k % 3 == 0 ? 0.0 : 0.3);
    EXPECT_EQ(indices(find_change_points(v, own_noise(20, 0.01, {}, 0.0))),
              indices(find_change_points(v)))
        << k;
  }
}

// AR(1) noise, value = exp(e), e_i = phi e_{i-1} + innovation, marginal
// spread 5 %: neighbouring runs share their noise, the levels wander, and a
// detector whose sigma comes from neighbouring differences sees steps.
TEST(ChangePoints, NoiseCarriedFromRunToRunMakesFarFewerFalseSteps) {
  std::mt19937_64 rng(1004);
  std::normal_distribution<double> z(0.0, 1.0);
  constexpr int kSeries = 600;
  constexpr double kPhi = 0.7, kSigma = 0.05;
  int before = 0, after = 0;
  for (int k = 0; k < kSeries; ++k) {
    std::vector<double> v(20);
    double e = kSigma * z(rng);
    for (double& x : v) {
      x = std::exp(e);
      e = kPhi * e + kSigma * std::sqrt(1 - kPhi * kPhi) * z(rng);
    }
    ChangePointOptions as_it_was;
    as_it_was.serial_correlation = false;
    before += find_change_points(v, as_it_was).empty() ? 0 : 1;
    after += find_change_points(v).empty() ? 0 : 1;
  }
  // Measured with this seed: 177 (29.5 %) before, 90 (15 %) after; over 2000
  // series in bench/change_point_grid.cpp, 29.2 % and 12.8 %. The issue's
  // target, 1 %, is out of reach at phi 0.7 without losing the steps that
  // are there (docs/ci.md, "The detector on a busy machine").
  EXPECT_GT(before, kSeries / 5);
  EXPECT_LT(after, before * 2 / 3);
}
