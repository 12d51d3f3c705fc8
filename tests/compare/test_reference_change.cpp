// compare refuses to compare errors measured against different references
// (method, spp, seed, Embree ISA, adaptive settings, cache key): such a
// change of error is the yardstick's, not the technique's. It names the
// jobs, the fields and both values, and exits 2; --allow-reference-change
// compares them anyway with a note; --metric none compares times only, which
// a reference change never blocks.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../common/text.h"
#include "cli_runner.h"
#include "results/compare.h"
#include "synthetic_run.h"

namespace {

using sb::record::JobRecord;
using sb::record::ReferenceRecord;
using sb::results::compare_runs;
using sb::results::CompareOptions;
using sb::results::Verdict;
using sb::test::against;
using sb::test::has;
using sb::test::make_record;
using sb::test::mc_reference;
using sb::test::noisy_samples;

// Jobs "a" and "b": frames around `ms` (±3 %), visibility RMSE `rmse`.
std::vector<sb::record::JobRecord> two_jobs(double ms, double rmse, uint32_t seed) {
  return {make_record("a", noisy_samples(ms, 0.03, 15, seed), rmse, 2 * rmse),
          make_record("b", noisy_samples(ms, 0.03, 15, seed + 1), rmse, 2 * rmse)};
}

TEST(ReferenceChange, ErrorsAgainstAnotherReferenceAreRefused) {
  // NEW's error is 0.03 higher, as a noisier 16-spp reference would make it.
  const auto base = against(two_jobs(20.0, 0.05, 1), mc_reference(64, "00aa"));
  const auto fresh = against(two_jobs(20.0, 0.08, 1), mc_reference(16, "11bb"));
  const auto r = sb::results::compare_runs(base, fresh, sb::results::CompareOptions{});
  ASSERT_EQ(r.jobs.size(), 2u);
  for (const auto& c : r.jobs) {
    EXPECT_TRUE(c.error_refused) << c.job_id;
    EXPECT_EQ(c.error, sb::results::Verdict::kNotCompared) << c.job_id;
    EXPECT_TRUE(has(c.note, "error not compared: the references differ (spp, cache_key")) << c.note;
    EXPECT_EQ(c.time, sb::results::Verdict::kUnchanged) << c.job_id;  // times are compared still
  }
  EXPECT_EQ(r.error_refused, 2);
  EXPECT_EQ(r.regressions, 0);
  EXPECT_EQ(sb::results::compare_exit_code(r), 2);
  ASSERT_EQ(r.references.size(), 1u);
  EXPECT_EQ(r.references[0].jobs, (std::vector<std::string>{"a", "b"}));
  const std::string t = sb::results::format_comparison(r, sb::results::CompareOptions{});
  for (const char* part : {"reference: differs for 2 job(s); their errors are not compared",
                           "spp: \"64\" vs \"16\"", "cache_key: \"00aa\" vs \"11bb\"", "jobs: a, b",
                           "2 with error not compared", "--allow-reference-change"})
    EXPECT_TRUE(has(t, part)) << part << "\n" << t;
}

// Each field alone is enough, and is the one named.
TEST(ReferenceChange, EachFieldIsChecked) {
  struct FieldCase {
    const char* field;
    void (*change)(sb::record::ReferenceRecord&);
    const char* values;
  } cases[] = {
      {"method", [](sb::record::ReferenceRecord& r) { r.method = "exact_clipper"; },
       "method: \"embree_stratified_packet16\" vs \"exact_clipper\""},
      {"spp", [](sb::record::ReferenceRecord& r) { r.spp = 256; }, "spp: \"64\" vs \"256\""},
      {"seed", [](sb::record::ReferenceRecord& r) { r.seed = 7; }, "seed: \"1\" vs \"7\""},
      {"embree_isa", [](sb::record::ReferenceRecord& r) { r.embree_isa = "avx512"; },
       "embree_isa: \"avx2\" vs \"avx512\""},
      {"adaptive.pilot_spp",
       [](sb::record::ReferenceRecord& r) {
         r.adaptive = sb::record::AdaptiveReferenceRecord{64, 0.01, 80, 256, {}, {}};
       },
       "adaptive.pilot_spp: \"4\" vs \"64\""},
      {"adaptive.target_std_error",
       [](sb::record::ReferenceRecord& r) {
         r.adaptive = sb::record::AdaptiveReferenceRecord{4, 0.011, 80, 256, {}, {}};
       },
       "adaptive.target_std_error: \"0.01\" vs \"0.011\""},
      {"cache_key", [](sb::record::ReferenceRecord& r) { r.cache_key = "ffff"; },
       "cache_key: \"00aa\" vs \"ffff\""},
  };
  sb::record::ReferenceRecord ref = mc_reference(64, "00aa");
  ref.adaptive = sb::record::AdaptiveReferenceRecord{4, 0.01, 20, 256, {}, {}};
  for (const auto& c : cases) {
    sb::record::ReferenceRecord changed = ref;
    c.change(changed);
    // The same error on both sides: refused all the same.
    const auto r = sb::results::compare_runs(against(two_jobs(20.0, 0.05, 1), ref),
                                             against(two_jobs(20.0, 0.05, 1), changed),
                                             sb::results::CompareOptions{});
    EXPECT_EQ(r.error_refused, 2) << c.field;
    ASSERT_EQ(r.references.size(), 1u) << c.field;
    EXPECT_EQ(r.references[0].differences, std::vector<std::string>{c.values}) << c.field;
    EXPECT_TRUE(has(r.jobs[0].note, std::string("(") + c.field + "; see above)")) << r.jobs[0].note;
  }
}

TEST(ReferenceChange, ARecordWithoutReferenceIsAnotherReference) {
  const auto base = two_jobs(20.0, 0.05, 1);  // no record["reference"]
  const auto r = sb::results::compare_runs(
      base, against(two_jobs(20.0, 0.05, 1), mc_reference(64, "00aa")), {});
  EXPECT_EQ(r.error_refused, 2);
  EXPECT_TRUE(has(sb::results::format_comparison(r, {}), "spp: (none) vs \"64\""))
      << sb::results::format_comparison(r, {});
}

TEST(ReferenceChange, AllowReferenceChangeComparesWithANote) {
  const auto base = against(two_jobs(20.0, 0.05, 1), mc_reference(64, "00aa"));
  const auto fresh = against(two_jobs(20.0, 0.08, 1), mc_reference(16, "11bb"));
  sb::results::CompareOptions allow;
  allow.allow_reference_change = true;
  const auto r = sb::results::compare_runs(base, fresh, allow);
  EXPECT_EQ(r.error_refused, 0);
  EXPECT_EQ(r.jobs[0].error, sb::results::Verdict::kRegression);
  EXPECT_EQ(sb::results::compare_exit_code(r), sb::results::kExitRegression);
  EXPECT_TRUE(has(r.jobs[0].note, "error compared anyway (--allow-reference-change)"))
      << r.jobs[0].note;
  const std::string t = sb::results::format_comparison(r, allow);
  EXPECT_TRUE(has(t, "errors compared anyway (--allow-reference-change)")) << t;
  EXPECT_TRUE(has(t, "spp: \"64\" vs \"16\"")) << t;
}

TEST(ReferenceChange, TimesOnlyAreNotBlocked) {
  sb::results::CompareOptions times;
  times.metric = "none";
  const auto base = against(two_jobs(20.0, 0.05, 1), mc_reference(64, "00aa"));
  auto r = sb::results::compare_runs(
      base, against(two_jobs(20.2, 0.08, 11), mc_reference(16, "11bb")), times);
  EXPECT_EQ(r.error_refused, 0);
  EXPECT_EQ(r.jobs[0].error, sb::results::Verdict::kNotCompared);
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kUnchanged);
  EXPECT_TRUE(r.references.empty());
  EXPECT_EQ(sb::results::compare_exit_code(r), 0);
  EXPECT_TRUE(has(sb::results::format_comparison(r, times), "error: not compared (--metric none)"));
  // A slowdown is found as before.
  r = sb::results::compare_runs(base, against(two_jobs(26.0, 0.08, 21), mc_reference(16, "11bb")),
                                times);
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kRegression);
  EXPECT_EQ(sb::results::compare_exit_code(r), sb::results::kExitRegression);
  // --metric none needs no metric in the records.
  auto bare = two_jobs(20.0, 0.05, 1);
  for (auto& rec : bare) rec.metrics.reset();
  EXPECT_NO_THROW(sb::results::compare_runs(bare, bare, times));
}

TEST(ReferenceChange, ASlowdownStillExitsFourBesideARefusedError) {
  const auto base = against(two_jobs(20.0, 0.05, 1), mc_reference(64, "00aa"));
  const auto r =
      sb::results::compare_runs(base, against(two_jobs(26.0, 0.05, 21), mc_reference(16, "11bb")),
                                sb::results::CompareOptions{});
  EXPECT_EQ(r.error_refused, 2);
  EXPECT_EQ(r.jobs[0].time, sb::results::Verdict::kRegression);
  EXPECT_EQ(sb::results::compare_exit_code(r), sb::results::kExitRegression);
}

TEST(ReferenceChange, TheSameReferenceIsCompared) {
  const auto ref = mc_reference(64, "00aa");
  auto r = sb::results::compare_runs(against(two_jobs(20.0, 0.05, 1), ref),
                                     against(two_jobs(20.0, 0.08, 1), ref),
                                     sb::results::CompareOptions{});
  EXPECT_EQ(r.error_refused, 0);
  EXPECT_EQ(r.jobs[0].error, sb::results::Verdict::kRegression);
  EXPECT_EQ(r.references_without_key, 0);
  // Keys absent on both sides (records from before they were always
  // written): compared on the other fields, and said so.
  const auto keyless = mc_reference(64, "");
  r = sb::results::compare_runs(against(two_jobs(20.0, 0.05, 1), keyless),
                                against(two_jobs(20.0, 0.05, 1), keyless),
                                sb::results::CompareOptions{});
  EXPECT_EQ(r.error_refused, 0);
  EXPECT_EQ(r.references_without_key, 2);
  EXPECT_TRUE(has(sb::results::format_comparison(r, {}), "2 job(s) have no reference cache_key"));
}

TEST(ReferenceChangeCli, RefusesExitsTwoAndNamesTheFields) {
  using sb::test::run_cli;
  using sb::test::write_run;
  const auto base =
      write_run("ref_base", against(two_jobs(20.0, 0.05, 1), mc_reference(64, "00aa")));
  const auto fresh =
      write_run("ref_new", against(two_jobs(20.0, 0.08, 1), mc_reference(16, "11bb")));
  auto r = run_cli("compare " + base + " " + fresh);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  for (const char* part : {"spp: \"64\" vs \"16\"", "jobs: a, b",
                           "the error of 2 job(s) was not compared", "--allow-reference-change"})
    EXPECT_TRUE(has(r.output, part)) << part << "\n" << r.output;
  r = run_cli("compare " + base + " " + fresh + " --allow-reference-change");
  EXPECT_EQ(r.exit_code, 4) << r.output;
  r = run_cli("compare " + base + " " + fresh + " --metric none");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  r = run_cli("compare " + base + " " + fresh + " --correction bonferroni");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(has(r.output, "--correction")) << r.output;
}

}  // namespace
