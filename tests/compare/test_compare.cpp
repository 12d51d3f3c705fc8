// compare_runs on synthetic records: an injected 30 % slowdown is flagged, a
// 1 % jitter is not, and error regressions are found by an absolute threshold.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "results/compare.h"
#include "synthetic_run.h"

namespace {

using sb::compare_runs;
using sb::CompareOptions;
using sb::JobRecord;
using sb::Verdict;
using sb::test::make_record;
using sb::test::noisy_samples;

constexpr int kFrames = 15;
constexpr double kNoise = 0.03;  // ±3 %

std::vector<JobRecord> one_job(double median_ms, uint32_t seed, double rmse = 0.05,
                               const std::string& id = "grid__320x240__pcf") {
  return {make_record(id, noisy_samples(median_ms, kNoise, kFrames, seed), rmse, 2 * rmse)};
}

TEST(Compare, FlagsAThirtyPercentSlowdown) {
  const auto r = compare_runs(one_job(20.0, 1), one_job(26.0, 2), CompareOptions{});
  ASSERT_EQ(r.jobs.size(), 1u);
  const auto& c = r.jobs[0];
  EXPECT_EQ(c.time, Verdict::kRegression);
  EXPECT_NEAR(c.change, 0.30, 0.05);
  ASSERT_TRUE(c.p.has_value());
  EXPECT_LT(*c.p, 1e-4);  // 15 vs 15 fully separated: p = 3.4e-6
  EXPECT_EQ(c.error, Verdict::kUnchanged);
  EXPECT_TRUE(c.regressed());
  EXPECT_EQ(r.regressions, 1);
}

TEST(Compare, IgnoresAOnePercentJitter) {
  // Several seeds: whatever the p-value of a 1 % shift in ±3 % noise, 1 % is
  // under the 10 % threshold, so it is never a regression.
  for (uint32_t seed = 1; seed <= 20; ++seed) {
    const auto r = compare_runs(one_job(20.0, seed), one_job(20.2, seed + 100), CompareOptions{});
    ASSERT_EQ(r.jobs.size(), 1u);
    EXPECT_EQ(r.jobs[0].time, Verdict::kUnchanged) << "seed " << seed;
    EXPECT_EQ(r.regressions, 0) << "seed " << seed;
  }
}

TEST(Compare, ImprovementIsNotARegression) {
  const auto r = compare_runs(one_job(26.0, 1), one_job(20.0, 2), CompareOptions{});
  EXPECT_EQ(r.jobs[0].time, Verdict::kImprovement);
  EXPECT_EQ(r.regressions, 0);
  EXPECT_EQ(r.improvements, 1);
}

TEST(Compare, NeedsBothSignificanceAndThreshold) {
  // Significant (no overlap) but only 5 % slower: under the threshold.
  std::vector<double> base, slower;
  for (int i = 0; i < kFrames; ++i) {
    base.push_back(20.0 + 0.01 * i);
    slower.push_back(21.0 + 0.01 * i);
  }
  auto r = compare_runs({make_record("j", base, 0.05, 0.1)}, {make_record("j", slower, 0.05, 0.1)},
                        CompareOptions{});
  EXPECT_LT(*r.jobs[0].p, 0.05);
  EXPECT_EQ(r.jobs[0].time, Verdict::kUnchanged);
  CompareOptions tight;
  tight.time_threshold = 0.02;
  r = compare_runs({make_record("j", base, 0.05, 0.1)}, {make_record("j", slower, 0.05, 0.1)},
                   tight);
  EXPECT_EQ(r.jobs[0].time, Verdict::kRegression);

  // 40 % slower by the median, but three noisy frames each: not significant.
  r = compare_runs({make_record("j", {10, 30, 20}, 0.05, 0.1)},
                   {make_record("j", {28, 12, 33}, 0.05, 0.1)}, CompareOptions{});
  EXPECT_GT(r.jobs[0].change, 0.10);
  EXPECT_GT(*r.jobs[0].p, 0.05);
  EXPECT_EQ(r.jobs[0].time, Verdict::kUnchanged);
}

// A technique 30 % slower inside a frame dominated by shared passes: the
// frame moves by under 10 %, the technique's own time by 30 %.
TEST(Compare, TechniqueTimingIsolatesTheTechnique) {
  auto with_technique = [](double technique_ms, uint32_t seed) {
    const auto t = noisy_samples(technique_ms, 0.01, kFrames, seed);
    std::vector<double> frame;
    frame.reserve(t.size());
    for (double v : t) frame.push_back(v + 20.0);  // G-buffer + shading
    JobRecord r = make_record("j", frame, 0.05, 0.1);
    r.timing->technique = sb::TimingSeries::of(t);
    return std::vector<JobRecord>{r};
  };
  const auto base = with_technique(5.0, 1), slower = with_technique(6.5, 2);
  auto r = compare_runs(base, slower, CompareOptions{});
  EXPECT_LT(r.jobs[0].change, 0.10);
  EXPECT_EQ(r.jobs[0].time, Verdict::kUnchanged);
  CompareOptions technique;
  technique.timing = "technique";
  r = compare_runs(base, slower, technique);
  EXPECT_NEAR(r.jobs[0].change, 0.30, 0.03);
  EXPECT_EQ(r.jobs[0].time, Verdict::kRegression);
  EXPECT_NE(sb::format_comparison(r, technique).find("U on technique times"), std::string::npos);
  technique.timing = "gbuffer";
  EXPECT_THROW(compare_runs(base, slower, technique), sb::InputError);
}

TEST(Compare, ErrorRegressionByAbsoluteThreshold) {
  auto r = compare_runs(one_job(20.0, 1, 0.050), one_job(20.0, 1, 0.060), CompareOptions{});
  EXPECT_EQ(r.jobs[0].time, Verdict::kUnchanged);  // identical samples: p = 1
  EXPECT_DOUBLE_EQ(*r.jobs[0].p, 1.0);
  EXPECT_EQ(r.jobs[0].error, Verdict::kRegression);
  EXPECT_EQ(r.regressions, 1);

  r = compare_runs(one_job(20.0, 1, 0.050), one_job(20.0, 1, 0.054), CompareOptions{});
  EXPECT_EQ(r.jobs[0].error, Verdict::kUnchanged);
  r = compare_runs(one_job(20.0, 1, 0.060), one_job(20.0, 1, 0.050), CompareOptions{});
  EXPECT_EQ(r.jobs[0].error, Verdict::kImprovement);

  // Another metric: the penumbra RMSE is twice the RMSE in these records.
  CompareOptions penumbra;
  penumbra.metric = "visibility.penumbra.rmse";
  r = compare_runs(one_job(20.0, 1, 0.050), one_job(20.0, 1, 0.054), penumbra);
  EXPECT_EQ(r.jobs[0].error, Verdict::kRegression);  // 0.100 -> 0.108

  // PSNR: higher is better, so a lower PSNR is the regression.
  CompareOptions psnr;
  psnr.metric = "metrics.visibility.all.psnr";
  r = compare_runs(one_job(20.0, 1, 0.050), one_job(20.0, 1, 0.060), psnr);
  EXPECT_EQ(r.jobs[0].error, Verdict::kRegression);

  // A NaN error where there was a number is a regression.
  auto nan_run = one_job(20.0, 1);
  nan_run[0].metrics->visibility.all.rmse = std::nan("");
  r = compare_runs(one_job(20.0, 1), nan_run, CompareOptions{});
  EXPECT_EQ(r.jobs[0].error, Verdict::kRegression);
}

TEST(Compare, UnknownMetricIsBadInput) {
  CompareOptions o;
  o.metric = "visibility.all.rsme";
  EXPECT_THROW(compare_runs(one_job(20.0, 1), one_job(20.0, 2), o), sb::InputError);
  o = CompareOptions{};
  o.alpha = 1.5;
  EXPECT_THROW(compare_runs(one_job(20.0, 1), one_job(20.0, 2), o), sb::InputError);
}

TEST(Compare, MatchesJobsByIdAndListsTheRest) {
  std::vector<JobRecord> base = one_job(20.0, 1, 0.05, "a");
  base.push_back(one_job(20.0, 2, 0.05, "b")[0]);
  std::vector<JobRecord> fresh = one_job(20.0, 3, 0.05, "b");
  fresh.push_back(one_job(20.0, 4, 0.05, "c")[0]);
  const auto r = compare_runs(base, fresh, CompareOptions{});
  ASSERT_EQ(r.jobs.size(), 1u);
  EXPECT_EQ(r.jobs[0].job_id, "b");
  EXPECT_EQ(r.only_base, std::vector<std::string>{"a"});
  EXPECT_EQ(r.only_new, std::vector<std::string>{"c"});
  const std::string table = sb::format_comparison(r, CompareOptions{});
  EXPECT_NE(table.find("only in BASE (1):\n  a\n"), std::string::npos) << table;
  EXPECT_NE(table.find("only in NEW (1):\n  c\n"), std::string::npos) << table;
}

TEST(Compare, AJobThatNowFailsIsARegression) {
  auto fresh = one_job(20.0, 2);
  fresh[0].status = sb::JobStatus::Failed;
  fresh[0].reason = "GL_OUT_OF_MEMORY";
  const auto r = compare_runs(one_job(20.0, 1), fresh, CompareOptions{});
  EXPECT_TRUE(r.jobs[0].regressed());
  EXPECT_EQ(r.regressions, 1);
  EXPECT_NE(sb::format_comparison(r, CompareOptions{}).find("failed in NEW: GL_OUT_OF_MEMORY"),
            std::string::npos);
}

TEST(Compare, RecordsWithoutSamplesAreNotTimed) {
  auto old = one_job(20.0, 1);
  old[0].timing->frame.samples_ms.clear();
  const auto r = compare_runs(old, one_job(26.0, 2), CompareOptions{});
  EXPECT_EQ(r.jobs[0].time, Verdict::kNotCompared);
  EXPECT_FALSE(r.jobs[0].p.has_value());
  EXPECT_NE(r.jobs[0].note.find("no frame samples"), std::string::npos);
  EXPECT_EQ(r.regressions, 0);
}

TEST(Compare, TableShowsTheVerdicts) {
  const auto r = compare_runs(one_job(20.0, 1), one_job(26.0, 2), CompareOptions{});
  const std::string t = sb::format_comparison(r, CompareOptions{});
  for (const char* s : {"grid__320x240__pcf", "REGRESSION", "base ms", "new ms", "rmse base",
                        "1 regression(s)", "+3"})
    EXPECT_NE(t.find(s), std::string::npos) << s << "\n" << t;
}

}  // namespace
