// compare_runs on synthetic records: an injected 30 % slowdown is flagged, a
// 1 % jitter is not, and error regressions are found by an absolute threshold.
// Absolute times from different hosts are refused (naming what differs);
// --normalize control compares per-frame ratios to the control whatever the
// hosts; --timing none compares errors only.
#include <gtest/gtest.h>

#include <cmath>

#include "../common/text.h"
#include "core/error.h"
#include "results/compare.h"
#include "synthetic_run.h"

namespace {

using sb::record::JobRecord;
using sb::results::compare_runs;
using sb::results::CompareOptions;
using sb::results::Verdict;
using sb::test::has;
using sb::test::make_controlled_record;
using sb::test::make_record;
using sb::test::noisy_samples;
using sb::test::on_host;

constexpr int kFrames = 15;
constexpr double kNoise = 0.03;  // ±3 %

std::vector<sb::record::JobRecord> one_job(double median_ms, uint32_t seed, double rmse = 0.05,
                                           const std::string& id = "grid__320x240__pcf") {
  return {make_record(id, noisy_samples(median_ms, kNoise, kFrames, seed), rmse, 2 * rmse)};
}

TEST(Compare, FlagsAThirtyPercentSlowdown) {
  const auto r =
      sb::results::compare_runs(one_job(20.0, 1), one_job(26.0, 2), sb::results::CompareOptions{});
  ASSERT_EQ(r.jobs.size(), 1u);
  const auto& c = r.jobs[0];
  EXPECT_EQ(c.time, sb::results::Verdict::kRegression);
  EXPECT_NEAR(c.change, 0.30, 0.05);
  ASSERT_TRUE(c.p.has_value());
  EXPECT_LT(*c.p, 1e-4);  // 15 vs 15 fully separated: p = 3.4e-6
  EXPECT_EQ(c.error, sb::results::Verdict::kUnchanged);
  EXPECT_TRUE(c.regressed());
  EXPECT_EQ(r.regressions, 1);
}

TEST(Compare, IgnoresAOnePercentJitter) {
  // Several seeds: whatever the p-value of a 1 % shift in ±3 % noise, 1 % is
  // under the 10 % threshold, so it is never a regression.
  for (uint32_t seed = 1; seed <= 20; ++seed) {
    const auto r = sb::results::compare_runs(one_job(20.0, seed), one_job(20.2, seed + 100),
                                             sb::results::CompareOptions{});
    ASSERT_EQ(r.jobs.size(), 1u);
    EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kUnchanged) << "seed " << seed;
    EXPECT_EQ(r.regressions, 0) << "seed " << seed;
  }
}

TEST(Compare, ImprovementIsNotARegression) {
  const auto r =
      sb::results::compare_runs(one_job(26.0, 1), one_job(20.0, 2), sb::results::CompareOptions{});
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kImprovement);
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
  auto r = sb::results::compare_runs({make_record("j", base, 0.05, 0.1)},
                                     {make_record("j", slower, 0.05, 0.1)},
                                     sb::results::CompareOptions{});
  EXPECT_LT(*r.jobs[0].p, 0.05);
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kUnchanged);
  sb::results::CompareOptions tight;
  tight.time_threshold = 0.02;
  r = sb::results::compare_runs({make_record("j", base, 0.05, 0.1)},
                                {make_record("j", slower, 0.05, 0.1)}, tight);
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kRegression);

  // 40 % slower by the median, but three noisy frames each: not significant.
  r = sb::results::compare_runs({make_record("j", {10, 30, 20}, 0.05, 0.1)},
                                {make_record("j", {28, 12, 33}, 0.05, 0.1)},
                                sb::results::CompareOptions{});
  EXPECT_GT(r.jobs[0].change, 0.10);
  EXPECT_GT(*r.jobs[0].p, 0.05);
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kUnchanged);
}

// A technique 30 % slower inside a frame dominated by shared passes: the
// frame moves by under 10 %, the technique's own time by 30 %.
TEST(Compare, TechniqueTimingIsolatesTheTechnique) {
  auto with_technique = [](double technique_ms, uint32_t seed) {
    const auto t = noisy_samples(technique_ms, 0.01, kFrames, seed);
    std::vector<double> frame;
    frame.reserve(t.size());
    for (double v : t) frame.push_back(v + 20.0);  // G-buffer + shading
    sb::record::JobRecord r = make_record("j", frame, 0.05, 0.1);
    r.timing->technique = sb::record::Series::of(t);
    return std::vector<sb::record::JobRecord>{r};
  };
  const auto base = with_technique(5.0, 1), slower = with_technique(6.5, 2);
  auto r = sb::results::compare_runs(base, slower, sb::results::CompareOptions{});
  EXPECT_LT(r.jobs[0].change, 0.10);
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kUnchanged);
  sb::results::CompareOptions technique;
  technique.timing = "technique";
  r = sb::results::compare_runs(base, slower, technique);
  EXPECT_NEAR(r.jobs[0].change, 0.30, 0.03);
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kRegression);
  EXPECT_NE(sb::results::format_comparison(r, technique).find("U on technique times"),
            std::string::npos);
  technique.timing = "gbuffer";
  EXPECT_THROW(sb::results::compare_runs(base, slower, technique), sb::core::InputError);
}

TEST(Compare, ErrorRegressionByAbsoluteThreshold) {
  auto r = sb::results::compare_runs(one_job(20.0, 1, 0.050), one_job(20.0, 1, 0.060),
                                     sb::results::CompareOptions{});
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kUnchanged);  // identical samples: p = 1
  EXPECT_DOUBLE_EQ(*r.jobs[0].p, 1.0);
  EXPECT_EQ(r.jobs[0].error, sb::results::Verdict::kRegression);
  EXPECT_EQ(r.regressions, 1);

  r = sb::results::compare_runs(one_job(20.0, 1, 0.050), one_job(20.0, 1, 0.054),
                                sb::results::CompareOptions{});
  EXPECT_EQ(r.jobs[0].error, sb::results::Verdict::kUnchanged);
  r = sb::results::compare_runs(one_job(20.0, 1, 0.060), one_job(20.0, 1, 0.050),
                                sb::results::CompareOptions{});
  EXPECT_EQ(r.jobs[0].error, sb::results::Verdict::kImprovement);

  // Another metric: the penumbra RMSE is twice the RMSE in these records.
  sb::results::CompareOptions penumbra;
  penumbra.metric = "visibility.penumbra.rmse";
  r = sb::results::compare_runs(one_job(20.0, 1, 0.050), one_job(20.0, 1, 0.054), penumbra);
  EXPECT_EQ(r.jobs[0].error, sb::results::Verdict::kRegression);  // 0.100 -> 0.108

  // PSNR: higher is better, so a lower PSNR is the regression.
  sb::results::CompareOptions psnr;
  psnr.metric = "metrics.visibility.all.psnr";
  r = sb::results::compare_runs(one_job(20.0, 1, 0.050), one_job(20.0, 1, 0.060), psnr);
  EXPECT_EQ(r.jobs[0].error, sb::results::Verdict::kRegression);

  // A NaN error where there was a number is a regression.
  auto nan_run = one_job(20.0, 1);
  nan_run[0].metrics->visibility.geometry->rmse = std::nan("");
  r = sb::results::compare_runs(one_job(20.0, 1), nan_run, sb::results::CompareOptions{});
  EXPECT_EQ(r.jobs[0].error, sb::results::Verdict::kRegression);
}

TEST(Compare, ABaselineWithoutTheMetricsRegionIsNotComparedOnErrors) {
  // A baseline recorded before `geometry` existed reads NaN there; taken as
  // a value, NaN -> 0.05 would be an "improvement" and the gate would pass
  // without comparing any error.
  auto old_base = one_job(20.0, 1, 0.050);
  old_base[0].metrics->visibility.geometry.reset();
  auto r =
      sb::results::compare_runs(old_base, one_job(20.0, 1, 0.500), sb::results::CompareOptions{});
  EXPECT_TRUE(r.jobs[0].error_refused);
  EXPECT_NE(r.jobs[0].error, sb::results::Verdict::kImprovement);
  EXPECT_NE(r.jobs[0].note.find("BASE's record has no visibility.geometry.rmse"), std::string::npos)
      << r.jobs[0].note;
  EXPECT_EQ(sb::results::compare_exit_code(r), 2);
  // Both sides without it; and a metric both sides hold still compares.
  r = sb::results::compare_runs(old_base, old_base, sb::results::CompareOptions{});
  EXPECT_NE(r.jobs[0].note.find("BASE and NEW's record"), std::string::npos) << r.jobs[0].note;
  sb::results::CompareOptions all;
  all.metric = "visibility.all.rmse";
  r = sb::results::compare_runs(old_base, one_job(20.0, 1, 0.500), all);
  EXPECT_FALSE(r.jobs[0].error_refused);
  EXPECT_EQ(r.jobs[0].error, sb::results::Verdict::kRegression);
}

TEST(Compare, UnknownMetricIsBadInput) {
  sb::results::CompareOptions o;
  o.metric = "visibility.all.rsme";
  EXPECT_THROW(sb::results::compare_runs(one_job(20.0, 1), one_job(20.0, 2), o),
               sb::core::InputError);
  o = sb::results::CompareOptions{};
  o.alpha = 1.5;
  EXPECT_THROW(sb::results::compare_runs(one_job(20.0, 1), one_job(20.0, 2), o),
               sb::core::InputError);
}

TEST(Compare, MatchesJobsByIdAndListsTheRest) {
  std::vector<sb::record::JobRecord> base = one_job(20.0, 1, 0.05, "a");
  base.push_back(one_job(20.0, 2, 0.05, "b")[0]);
  std::vector<sb::record::JobRecord> fresh = one_job(20.0, 3, 0.05, "b");
  fresh.push_back(one_job(20.0, 4, 0.05, "c")[0]);
  const auto r = sb::results::compare_runs(base, fresh, sb::results::CompareOptions{});
  ASSERT_EQ(r.jobs.size(), 1u);
  EXPECT_EQ(r.jobs[0].job_id, "b");
  EXPECT_EQ(r.only_base, std::vector<std::string>{"a"});
  EXPECT_EQ(r.only_new, std::vector<std::string>{"c"});
  const std::string table = sb::results::format_comparison(r, sb::results::CompareOptions{});
  EXPECT_NE(table.find("only in BASE (1):\n  a\n"), std::string::npos) << table;
  EXPECT_NE(table.find("only in NEW (1):\n  c\n"), std::string::npos) << table;
}

TEST(Compare, AJobThatNowFailsIsARegression) {
  auto fresh = one_job(20.0, 2);
  fresh[0].status = sb::record::JobStatus::Failed;
  fresh[0].reason = "GL_OUT_OF_MEMORY";
  const auto r = sb::results::compare_runs(one_job(20.0, 1), fresh, sb::results::CompareOptions{});
  EXPECT_TRUE(r.jobs[0].regressed());
  EXPECT_EQ(r.regressions, 1);
  EXPECT_NE(sb::results::format_comparison(r, sb::results::CompareOptions{})
                .find("failed in NEW: GL_OUT_OF_MEMORY"),
            std::string::npos);
}

TEST(Compare, RecordsWithoutSamplesAreNotTimed) {
  auto old = one_job(20.0, 1);
  old[0].timing->frame.samples.clear();
  const auto r = sb::results::compare_runs(old, one_job(26.0, 2), sb::results::CompareOptions{});
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kNotCompared);
  EXPECT_FALSE(r.jobs[0].p.has_value());
  EXPECT_NE(r.jobs[0].note.find("no frame samples"), std::string::npos);
  EXPECT_EQ(r.regressions, 0);
}

TEST(Compare, TableShowsTheVerdicts) {
  const auto r =
      sb::results::compare_runs(one_job(20.0, 1), one_job(26.0, 2), sb::results::CompareOptions{});
  const std::string t = sb::results::format_comparison(r, sb::results::CompareOptions{});
  for (const char* s : {"grid__320x240__pcf", "REGRESSION", "base ms", "new ms", "rmse base",
                        "1 regression(s)", "+3"})
    EXPECT_NE(t.find(s), std::string::npos) << s << "\n" << t;
}

// ---- hosts, --normalize control, --timing none ----

constexpr const char* kAmd = "AMD EPYC 7B13";
constexpr const char* kIntel = "Intel Xeon Platinum 8481C";
constexpr const char* kWide = "llvmpipe (LLVM 15.0.6, 512 bits)";

TEST(CompareHosts, DifferentCpusRefuseAbsoluteTimes) {
  // Twice as slow on the other machine: not a regression, not compared.
  const auto base = on_host(one_job(20.0, 1), kAmd);
  const auto fresh = on_host(one_job(40.0, 2), kIntel, kWide);
  const auto r = sb::results::compare_runs(base, fresh, sb::results::CompareOptions{});
  ASSERT_EQ(r.jobs.size(), 1u);
  const auto& c = r.jobs[0];
  EXPECT_EQ(c.time, sb::results::Verdict::kNotCompared);
  EXPECT_TRUE(c.time_refused);
  EXPECT_FALSE(c.p.has_value());
  EXPECT_TRUE(has(c.note, "cpu.model")) << c.note;
  EXPECT_TRUE(has(c.note, "gl_renderer")) << c.note;
  EXPECT_EQ(c.error, sb::results::Verdict::kUnchanged);  // errors are compared whatever the host
  EXPECT_EQ(r.time_refused, 1);
  EXPECT_EQ(r.regressions, 0);
  EXPECT_EQ(sb::results::compare_exit_code(r), 2);  // a gate that skipped timing is not green
  ASSERT_EQ(r.hosts.size(), 1u);
  EXPECT_FALSE(r.hosts[0].same());
  const std::string t = sb::results::format_comparison(r, sb::results::CompareOptions{});
  for (const char* part :
       {"cpu.model: \"AMD EPYC 7B13\" vs \"Intel Xeon Platinum 8481C\"",
        "gl_renderer: \"llvmpipe (test)\" vs \"llvmpipe (LLVM 15.0.6, 512 bits)\"",
        "error metrics are compared whatever the host", "--normalize control", "not compared",
        "absolute (--normalize none)", "1 with time not compared"})
    EXPECT_TRUE(has(t, part)) << part << "\n" << t;
  EXPECT_FALSE(has(t, "same host fingerprint")) << t;

  // An error regression on top: exit 4, not 2.
  const auto worse = on_host(one_job(40.0, 2, 0.08), kIntel);
  const auto w = sb::results::compare_runs(base, worse, sb::results::CompareOptions{});
  EXPECT_EQ(w.jobs[0].error, sb::results::Verdict::kRegression);
  EXPECT_EQ(sb::results::compare_exit_code(w), sb::results::kExitRegression);
}

TEST(CompareHosts, SameFingerprintIsCompared) {
  const auto r =
      sb::results::compare_runs(on_host(one_job(20.0, 1), kAmd), on_host(one_job(26.0, 2), kAmd),
                                sb::results::CompareOptions{});
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kRegression);
  EXPECT_FALSE(r.jobs[0].time_refused);
  EXPECT_EQ(r.time_refused, 0);
  EXPECT_EQ(sb::results::compare_exit_code(r), sb::results::kExitRegression);
  const std::string t = sb::results::format_comparison(r, sb::results::CompareOptions{});
  EXPECT_TRUE(has(t, "host: same host fingerprint (" +
                         on_host(one_job(20.0, 1), kAmd)[0].host.fingerprint.value() + ")"))
      << t;
  // Unchanged code on the same host: exit 0.
  const auto same =
      sb::results::compare_runs(on_host(one_job(20.0, 1), kAmd), on_host(one_job(20.2, 3), kAmd),
                                sb::results::CompareOptions{});
  EXPECT_EQ(sb::results::compare_exit_code(same), 0);
}

TEST(CompareHosts, ARecordWithoutFingerprintIsRefused) {
  auto old = one_job(20.0, 1);
  old[0].host = sb::record::HostRecord{};  // as written before host fingerprints
  old[0].host.hardware_threads = 2;
  const auto r = sb::results::compare_runs(old, one_job(20.0, 2), sb::results::CompareOptions{});
  EXPECT_TRUE(r.jobs[0].time_refused);
  EXPECT_EQ(sb::results::compare_exit_code(r), 2);
  EXPECT_TRUE(has(sb::results::format_comparison(r, sb::results::CompareOptions{}),
                  "BASE's records have no host fingerprint"));
}

// n ratios around `median` with ±3 % noise, and a control frame time around
// `control_ms` with ±3 % noise.
std::vector<sb::record::JobRecord> controlled(double control_ms, double ratio, uint32_t seed,
                                              double rmse = 0.05,
                                              const std::string& control = "none") {
  return {make_controlled_record("grid__320x240__pcf",
                                 noisy_samples(control_ms, kNoise, kFrames, seed),
                                 noisy_samples(ratio, kNoise, kFrames, seed + 50), rmse, control)};
}

sb::results::CompareOptions normalized(const std::string& timing = "frame") {
  sb::results::CompareOptions o;
  o.normalize = "control";
  o.timing = timing;
  return o;
}

TEST(CompareHosts, NormalizeControlComparesRatiosAcrossHosts) {
  const auto base = on_host(controlled(10.0, 2.0, 1), kAmd);
  // The other machine is twice as slow throughout: the ratios do not move.
  const auto slower_host = on_host(controlled(20.0, 2.0, 2), kIntel, kWide);
  auto r = sb::results::compare_runs(base, slower_host, normalized());
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kUnchanged);
  EXPECT_FALSE(r.jobs[0].time_refused);
  EXPECT_NEAR(r.jobs[0].base_median_ms, 2.0, 0.1);  // a ratio, not ms
  EXPECT_NEAR(r.jobs[0].change, 0.0, 0.05);
  EXPECT_EQ(sb::results::compare_exit_code(r), 0);
  std::string t = sb::results::format_comparison(r, normalized());
  for (const char* part : {"frame/control ratios (--normalize control)", "base ratio",
                           "times are compared as ratios to the control", "cpu.model"})
    EXPECT_TRUE(has(t, part)) << part << "\n" << t;
  // ... while absolutely it is twice as slow, which --normalize none refuses.
  EXPECT_TRUE(sb::results::compare_runs(base, slower_host, sb::results::CompareOptions{})
                  .jobs[0]
                  .time_refused);

  // The job itself 30 % slower against its control: a regression.
  const auto slower_job = on_host(controlled(20.0, 2.6, 3), kIntel, kWide);
  r = sb::results::compare_runs(base, slower_job, normalized());
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kRegression);
  EXPECT_NEAR(r.jobs[0].change, 0.30, 0.05);
  EXPECT_EQ(sb::results::compare_exit_code(r), sb::results::kExitRegression);
  t = sb::results::format_comparison(r, normalized());
  EXPECT_TRUE(has(t, "regression: frame/control ratio +")) << t;

  // --timing technique: technique frame i / control frame i (two thirds of the ratio).
  r = sb::results::compare_runs(base, slower_job, normalized("technique"));
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kRegression);
  EXPECT_NEAR(r.jobs[0].base_median_ms, 2.0 * 2 / 3, 0.1);
  r = sb::results::compare_runs(base, slower_host, normalized("technique"));
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kUnchanged);
}

TEST(CompareHosts, NormalizeControlWithoutControlIsRefused) {
  const auto base = one_job(20.0, 1);  // no timing.control
  const auto r = sb::results::compare_runs(base, controlled(10.0, 2.0, 2), normalized());
  EXPECT_TRUE(r.jobs[0].time_refused);
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kNotCompared);
  EXPECT_TRUE(has(r.jobs[0].note, "no timing.control in BASE")) << r.jobs[0].note;
  EXPECT_EQ(r.jobs[0].error, sb::results::Verdict::kUnchanged);
  EXPECT_EQ(sb::results::compare_exit_code(r), 2);
}

TEST(CompareHosts, DifferentControlTechniquesAreBadInput) {
  const auto base = controlled(10.0, 2.0, 1, 0.05, "none");
  const auto fresh = controlled(10.0, 2.0, 2, 0.05, "shadow_map/size=1024");
  try {
    sb::results::compare_runs(base, fresh, normalized());
    ADD_FAILURE() << "expected an InputError";
  } catch (const sb::core::InputError& e) {
    EXPECT_TRUE(has(e.what(), "shadow_map/size=1024")) << e.what();
  }
  // Absolute times do not look at the control.
  EXPECT_NO_THROW(sb::results::compare_runs(base, fresh, sb::results::CompareOptions{}));
}

TEST(CompareHosts, TimingNoneComparesErrorsOnly) {
  sb::results::CompareOptions none;
  none.timing = "none";
  const auto base = on_host(one_job(20.0, 1), kAmd);
  auto r = sb::results::compare_runs(base, on_host(one_job(40.0, 2), kIntel), none);
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kNotCompared);
  EXPECT_FALSE(r.jobs[0].time_refused);
  EXPECT_EQ(r.jobs[0].error, sb::results::Verdict::kUnchanged);
  EXPECT_EQ(sb::results::compare_exit_code(r), 0);
  EXPECT_TRUE(has(sb::results::format_comparison(r, none), "time: not compared (--timing none)"));
  r = sb::results::compare_runs(base, on_host(one_job(40.0, 2, 0.08), kIntel), none);
  EXPECT_EQ(sb::results::compare_exit_code(r), sb::results::kExitRegression);
}

TEST(CompareHosts, ADifferentBuildIsShownNotRefused) {
  auto fresh = one_job(26.0, 2);
  fresh[0].build.compiler = "Clang 16.0.6";
  fresh[0].build.fingerprint = sb::record::build_fingerprint(fresh[0].build);
  const auto r = sb::results::compare_runs(one_job(20.0, 1), fresh, sb::results::CompareOptions{});
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kRegression);
  const std::string t = sb::results::format_comparison(r, sb::results::CompareOptions{});
  EXPECT_TRUE(has(t, "build: differs (shown, not refused)")) << t;
  EXPECT_TRUE(has(t, "compiler: (none) vs \"Clang 16.0.6\"")) << t;
}

TEST(CompareHosts, ADifferentPluginIsShownPerTechniqueNotRefused) {
  auto base = one_job(20.0, 1, 0.05, "grid__320x240__pcf");
  base.push_back(one_job(20.0, 3, 0.05, "grid__320x240__map")[0]);
  auto fresh = one_job(20.0, 2, 0.05, "grid__320x240__pcf");
  fresh.push_back(one_job(20.0, 4, 0.05, "grid__320x240__map")[0]);
  const std::string old_hash(64, 'a'), new_hash(64, 'b');
  const auto name = [](sb::record::JobRecord& r, const std::string& technique,
                       const std::string& sha256) {
    r.technique.name = technique;
    r.technique.plugin = sb::record::PluginRecord{"shadow_map.so", 1000, sha256, 1};
  };
  name(base[0], "pcf_box", old_hash);
  name(base[1], "shadow_map", old_hash);
  name(fresh[0], "pcf_box", new_hash);
  name(fresh[1], "shadow_map", old_hash);  // this one's module is unchanged
  const auto r = sb::results::compare_runs(base, fresh, sb::results::CompareOptions{});
  EXPECT_EQ(sb::results::compare_exit_code(r), 0);  // information, not a refusal
  const std::string t = sb::results::format_comparison(r, sb::results::CompareOptions{});
  EXPECT_TRUE(has(t,
                  "plugin shadow_map.so differs: sha256 aaaaaaaaaaaa.. vs bbbbbbbbbbbb.. "
                  "(technique pcf_box; shown, not refused)"))
      << t;
  EXPECT_FALSE(has(t, "technique shadow_map;")) << t;
  // Records that name no plugin (older ones) say nothing either way.
  base[0].technique.plugin.reset();
  EXPECT_FALSE(has(sb::results::format_comparison(
                       sb::results::compare_runs(base, fresh, sb::results::CompareOptions{}), {}),
                   "plugin shadow_map.so differs"));
}

TEST(CompareHosts, UnknownNormalizeOrTimingIsBadInput) {
  sb::results::CompareOptions o;
  o.normalize = "ratio";
  EXPECT_THROW(sb::results::check_options(o), sb::core::InputError);
  o = sb::results::CompareOptions{};
  o.timing = "shading";
  EXPECT_THROW(sb::results::check_options(o), sb::core::InputError);
  o.timing = "none";
  EXPECT_NO_THROW(sb::results::check_options(o));
}

}  // namespace

TEST(CompareHosts, AJobThatIsItsOwnControlIsNotJudgedOnRatios) {
  // The control timed as a job too: its ratio is 1 whatever becomes of it,
  // so it is left out of the ratio verdicts and of the correction's family.
  const auto as_control = [](std::vector<sb::record::JobRecord> run) {
    for (sb::record::JobRecord& r : run) r.technique_variant = r.timing->control->technique;
    return run;
  };
  const auto base = as_control(controlled(10.0, 1.0, 1, 0.05, "shadow_map/size=1024"));
  const auto fresh = as_control(controlled(10.0, 1.0, 2, 0.05, "shadow_map/size=1024"));
  auto r = sb::results::compare_runs(base, fresh, normalized());
  EXPECT_FALSE(r.jobs[0].p.has_value());
  EXPECT_EQ(r.time_tests, 0);
  EXPECT_FALSE(r.jobs[0].time_refused);
  EXPECT_TRUE(has(r.jobs[0].note, "this job is the control")) << r.jobs[0].note;
  EXPECT_EQ(sb::results::compare_exit_code(r), 0);
  // Absolute times (same host) are still judged: there the job is a job.
  r = sb::results::compare_runs(base, fresh, sb::results::CompareOptions{});
  EXPECT_TRUE(r.jobs[0].p.has_value());
}

TEST(CompareHosts, DifferentTimingBracketsAreNotComparedOnTime) {
  // Same host, same samples: only the bracket rule differs, and it decides
  // what a frame's time includes.
  auto base = controlled(10.0, 2.0, 1), fresh = controlled(10.0, 2.0, 2);
  base[0].timing_source = "gl_timer_query";
  fresh[0].timing_source = "gl_timestamp_query";
  for (const sb::results::CompareOptions& o : {sb::results::CompareOptions{}, normalized()}) {
    const auto r = sb::results::compare_runs(base, fresh, o);
    EXPECT_TRUE(r.jobs[0].time_refused);
    EXPECT_TRUE(has(r.jobs[0].note,
                    "the timing brackets differ (BASE gl_timer_query, NEW "
                    "gl_timestamp_query"))
        << r.jobs[0].note;
    EXPECT_EQ(r.jobs[0].error, sb::results::Verdict::kUnchanged);  // errors do not depend on it
    EXPECT_EQ(sb::results::compare_exit_code(r), 2);
  }
  fresh[0].timing_source = "gl_timer_query";
  EXPECT_FALSE(sb::results::compare_runs(base, fresh, normalized()).jobs[0].time_refused);
}
