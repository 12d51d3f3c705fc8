// The median's 95 % interval from order statistics (record/median_interval.h)
// and the noise judgement made of it (record/timing_record.h, NoiseRecord):
// ranks against scipy's binomial, a hand-computed case, the interval of given
// samples, and a wide and a tight sample set judged against a threshold.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "record/median_interval.h"
#include "record/timing_record.h"
#include "sample_records.h"

namespace sb {

using record::ControlTiming;
using record::median_ci_ranks;
using record::MedianRanks;
using record::NoiseRecord;
using record::Series;
using record::TimingRecord;

namespace {

struct Expected {
  size_t n, lower, upper;
  double coverage;
};

// tests/record/scipy_median_ci_values.py (scipy 1.10.1): j, n + 1 - j and
// 1 - 2 binom.cdf(j - 1, n, 0.5); the range (j = 1) for n < 6.
const Expected kScipy[] = {
    {1, 1, 1, 0.0},
    {2, 1, 2, 0.5},
    {3, 1, 3, 0.75},
    {4, 1, 4, 0.875},
    {5, 1, 5, 0.9375},
    {6, 1, 6, 0.96875},
    {7, 1, 7, 0.984375},
    {8, 1, 8, 0.9921875},
    {9, 2, 8, 0.9609375},
    {10, 2, 9, 0.978515625},
    {11, 2, 10, 0.98828125},
    {12, 3, 10, 0.96142578125},
    {15, 4, 12, 0.96484375},
    {20, 6, 15, 0.9586105346679688},
    {25, 8, 18, 0.9567147493362427},
    {30, 10, 21, 0.9572260547429323},
    {40, 14, 27, 0.9615226917157997},
    {50, 18, 33, 0.9671608624357315},
    {71, 27, 45, 0.9680728379167877},
    {100, 40, 61, 0.9647997997822951},
    {1000, 469, 532, 0.9537088026395019},
    {100000, 49690, 50311, 0.9504442853304775},
};

TEST(MedianInterval, RanksAreScipysBinomialOrderStatistics) {
  for (const Expected& e : kScipy) {
    const MedianRanks r = median_ci_ranks(e.n);
    EXPECT_EQ(r.lower, e.lower) << "n = " << e.n;
    EXPECT_EQ(r.upper, e.upper) << "n = " << e.n;
    EXPECT_NEAR(r.coverage, e.coverage, 1e-9) << "n = " << e.n;
  }
}

TEST(MedianInterval, TenSamplesByHand) {
  // P(B <= 1) = (1 + 10) / 1024 = 0.0107 <= 2.5 %, P(B <= 2) = 56 / 1024 =
  // 0.0547 > 2.5 %: j = 2, the interval [x_(2), x_(9)], coverage 1 - 22/1024.
  const MedianRanks r = median_ci_ranks(10);
  EXPECT_EQ(r.lower, 2u);
  EXPECT_EQ(r.upper, 9u);
  EXPECT_DOUBLE_EQ(r.coverage, 1.0 - 22.0 / 1024.0);
}

TEST(MedianInterval, FewerThanSixSamplesGiveTheRangeBelowNinetyFivePercent) {
  // Six is the first n whose range reaches 95 %: 2 / 2^6 = 3.1 % outside.
  EXPECT_GE(median_ci_ranks(6).coverage, 0.95);
  for (size_t n = 1; n < 6; ++n) {
    const MedianRanks r = median_ci_ranks(n);
    EXPECT_EQ(r.lower, 1u);
    EXPECT_EQ(r.upper, n);
    EXPECT_DOUBLE_EQ(r.coverage, 1.0 - std::pow(0.5, double(n) - 1.0)) << n;
    EXPECT_LT(r.coverage, 0.95);
  }
  EXPECT_EQ(median_ci_ranks(0).lower, 0u);
}

TEST(MedianInterval, ASeriesKeepsItsIntervalsEndsAndRelativeHalfWidth) {
  // Ten samples out of order: sorted 1, 2, ..., 9, 20; x_(2) = 2, x_(9) = 9,
  // median 5.5, half-width 3.5 / 5.5.
  const Series s = Series::of({9, 1, 20, 3, 2, 8, 4, 7, 6, 5});
  EXPECT_DOUBLE_EQ(s.median, 5.5);
  EXPECT_DOUBLE_EQ(s.median_ci_lo, 2.0);
  EXPECT_DOUBLE_EQ(s.median_ci_hi, 9.0);
  EXPECT_DOUBLE_EQ(s.median_ci_rel, 3.5 / 5.5);
  EXPECT_DOUBLE_EQ(s.median_ci_coverage, 1.0 - 22.0 / 1024.0);
  // The outlier moves no end: the interval is of ranks, not of spread.
  const Series t = Series::of({9, 1, 2000, 3, 2, 8, 4, 7, 6, 5});
  EXPECT_DOUBLE_EQ(t.median_ci_hi, 9.0);
}

TEST(MedianInterval, ARecordWithoutTheIntervalReadsAsZero) {
  // Records written before it lack the keys (Presence::OlderLack).
  TimingRecord t;
  t.frame = Series::of({1, 2, 3, 4, 5, 6});
  t.technique = t.frame;
  nlohmann::json written = t.to_json();
  for (const char* key :
       {"median_ci_lo_ms", "median_ci_hi_ms", "median_ci_rel", "median_ci_coverage"}) {
    ASSERT_TRUE(written["frame"].contains(key)) << key;
    written["frame"].erase(key);
  }
  const TimingRecord read = TimingRecord::from_json(record::Fields(written, "/timing"));
  EXPECT_EQ(read.frame.median_ci_rel, 0.0);
  EXPECT_FALSE(read.noise.has_value());
}

TEST(NoiseJudgement, AWideSampleSetIsNoisyAndATightOneIsNot) {
  TimingRecord wide;
  wide.frame = Series::of(test::spread_frames(3.0));  // ±30 %: x_(6) = 8.5, x_(15) = 11.2
  const NoiseRecord w = NoiseRecord::judge(wide, 0.05);
  EXPECT_NEAR(w.frame_ci_rel, (11.2 - 8.5) / 2.0 / wide.frame.median, 1e-12);
  EXPECT_GT(w.frame_ci_rel, 0.05);
  EXPECT_TRUE(w.noisy);
  EXPECT_EQ(w.threshold, 0.05);
  EXPECT_FALSE(w.frame_ratio_ci_rel.has_value());

  TimingRecord tight;
  tight.frame = Series::of(test::spread_frames(0.2));  // ±2 %
  const NoiseRecord n = NoiseRecord::judge(tight, 0.05);
  EXPECT_LT(n.frame_ci_rel, 0.05);
  EXPECT_FALSE(n.noisy);
  // The threshold decides: the same tight frames against a tighter one.
  EXPECT_TRUE(NoiseRecord::judge(tight, n.frame_ci_rel / 2).noisy);
}

TEST(NoiseJudgement, ANoisyFrameRatioMakesTheJobNoisyButTheControlsFramesDoNot) {
  TimingRecord t;
  t.frame = Series::of(test::spread_frames(0.2));
  ControlTiming c;
  c.frame = Series::of(test::spread_frames(3.0));        // the control's own frames: noted only
  c.frame_ratio = Series::of(test::spread_frames(0.1));  // tight
  t.control = c;
  NoiseRecord n = NoiseRecord::judge(t, 0.05);
  ASSERT_TRUE(n.control_frame_ci_rel && n.frame_ratio_ci_rel);
  EXPECT_GT(*n.control_frame_ci_rel, 0.05);
  EXPECT_FALSE(n.noisy);
  t.control->frame_ratio = Series::of(test::spread_frames(3.0));
  n = NoiseRecord::judge(t, 0.05);
  EXPECT_TRUE(n.noisy);
  EXPECT_DOUBLE_EQ(n.judged_ci_rel(), *n.frame_ratio_ci_rel);
}

}  // namespace

}  // namespace sb
