// Rankings with their uncertainty (results/rank_ties.h): the order, the
// Mann–Whitney p-values and the Holm decisions against
// tests/results/rank_ties_values.py (scipy.stats.mannwhitneyu, Debian 12's
// scipy 1.10.1, and Holm's rejection rule as stated in his paper), whose
// printout is pasted below; and, with constructed samples, which samples
// are ranked and that the control is left out.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../common/text.h"
#include "../metrics/test_util.h"
#include "control_run.h"
#include "results/html_report.h"
#include "results/rank_ties.h"
#include "results/ranking_tables.h"
#include "results/report.h"

namespace sb {

using record::JobRecord;
using results::rank_by_time;
using results::Ranking;
using results::RankSamples;

namespace {

// rank_ties_values.py's six variants, in the group's order.
const double kBases[] = {1.46, 1.17, 2.63, 1.29, 1.47, 1.19};
const int kMults[] = {3, 5, 7, 11, 13, 17};

// Its printout:
//   order (input indices): [1, 5, 3, 0, 4, 2]
//   raw p of each adjacent pair: ['0.029205409568445008', '2.6098527879558533e-10',
//     '3.019859359162157e-11', '0.2904721494938346', '3.019859359162157e-11']
//   tied with the one above: [False, True, False, False, True, False]
// The first pair's raw p is below 0.05, yet Holm over five pairs ties it.
const std::vector<int> kOrder = {1, 5, 3, 0, 4, 2};
const std::vector<double> kRawP = {0.029205409568445008, 2.6098527879558533e-10,
                                   3.019859359162157e-11, 0.2904721494938346,
                                   3.019859359162157e-11};
const std::vector<bool> kTied = {false, true, false, false, true, false};

std::string name(int i) { return "t" + std::to_string(i); }

// The six variants: `ratios` as timing.control.frame_ratio against the
// control `none` (with `none`'s own record), else as the frame times.
// The frame times of a ratio run rank the other way round (the slowest
// ratio the fastest frame), so that the samples used show in the order.
std::vector<JobRecord> oracle_records(bool ratios) {
  std::vector<JobRecord> out;
  for (int i = 0; i < 6; ++i) {
    JobRecord r = test::identity_record("s", "64x48", name(i));
    const std::vector<double> s = test::spread_samples(kBases[i], kMults[i]);
    if (ratios) {
      r.timing = test::coarse_timing(test::spread_samples(10.0 / kBases[i], kMults[i]),
                                     std::vector<double>(30, 1.0));
      record::ControlTiming c;
      c.technique = "none";
      c.frame = record::Series::of(std::vector<double>(30, 1.0));
      c.frame_ratio = record::Series::of(s);
      r.timing->control = c;
    } else {
      r.timing = test::coarse_timing(s, std::vector<double>(30, 0.5));
    }
    out.push_back(r);
  }
  if (ratios) {  // the control: fastest, ratio 1, and not ranked
    JobRecord r = test::identity_record("s", "64x48", "none");
    r.timing = test::coarse_timing(std::vector<double>(30, 1.0), std::vector<double>(30, 0.1));
    record::ControlTiming c;
    c.technique = "none";
    c.frame = r.timing->frame;
    c.frame_ratio = record::Series::of(std::vector<double>(30, 1.0));
    r.timing->control = c;
    out.insert(out.begin(), r);
  }
  return out;
}

void expect_oracle(const Ranking& ranking) {
  ASSERT_EQ(ranking.entries.size(), 6U);
  EXPECT_EQ(ranking.pairs_tested(), 5U);
  for (size_t k = 0; k < 6; ++k) {
    const auto& e = ranking.entries[k];
    EXPECT_EQ(e.record->technique_variant, name(kOrder[k])) << k;
    EXPECT_EQ(e.rank, int(k + 1));
    EXPECT_EQ(e.count, 30U);
    EXPECT_EQ(e.tied_with_above, kTied[k]) << k;
    if (k == 0) {
      EXPECT_FALSE(e.p_adjusted);
      continue;
    }
    ASSERT_TRUE(e.p_adjusted);
    // Holm never lowers a p-value, and at most multiplies it by the pairs.
    EXPECT_GE(*e.p_adjusted, kRawP[k - 1] * (1 - 1e-9)) << k;
    EXPECT_LE(*e.p_adjusted, std::min(1.0, 5 * kRawP[k - 1]) * (1 + 1e-9)) << k;
  }
  // Tie groups: a new one at each significant step.
  std::vector<int> groups;
  for (const auto& e : ranking.entries) groups.push_back(e.tie_group);
  EXPECT_EQ(groups, (std::vector<int>{1, 1, 2, 3, 3, 4}));
}

TEST(RankTies, FrameTimesWithoutAControlMatchScipyAndHolm) {
  const auto records = oracle_records(false);
  const Ranking r = rank_by_time(test::record_pointers(records));
  EXPECT_EQ(r.samples, RankSamples::kFrameMs);
  expect_oracle(r);
}

TEST(RankTies, RatiosToTheControlAreRankedAndTheControlIsLeftOut) {
  const auto records = oracle_records(true);
  const Ranking r = rank_by_time(test::record_pointers(records));
  EXPECT_EQ(r.samples, RankSamples::kControlRatio);
  EXPECT_EQ(r.control, "none");
  expect_oracle(r);  // by the ratios, not the frame times, and no `none`
}

// Obvious cases: 30 frames of two variants that do not overlap are
// different (p ~ 3e-11); two variants with the very same samples are not (p = 1).
TEST(RankTies, SeparatedSamplesDifferAndEqualOnesTie) {
  std::vector<JobRecord> records;
  for (const auto& [n, median, a] : std::vector<std::tuple<std::string, double, int>>{
           {"slow", 20.0, 3}, {"fast", 10.0, 5}, {"fast_twin", 10.0, 5}}) {
    JobRecord r = test::identity_record("s", "64x48", n);
    r.timing = test::coarse_timing(test::spread_samples(median, a), std::vector<double>(30, 1));
    records.push_back(r);
  }
  const Ranking r = rank_by_time(test::record_pointers(records));
  ASSERT_EQ(r.entries.size(), 3U);
  EXPECT_EQ(r.entries[0].record->technique_variant, "fast");  // equal medians keep their order
  EXPECT_EQ(r.entries[1].record->technique_variant, "fast_twin");
  EXPECT_TRUE(r.entries[1].tied_with_above);
  EXPECT_DOUBLE_EQ(*r.entries[1].p_adjusted, 1.0);
  EXPECT_FALSE(r.entries[2].tied_with_above);
  EXPECT_LT(*r.entries[2].p_adjusted, 1e-9);
  EXPECT_EQ(results::rank_cell(r.entries[1]), "2 \u2248");
  EXPECT_EQ(results::rank_cell(r.entries[2]), "3");
}

TEST(RankTies, SummaryAndHtmlShowTheRankingTiesAndTheLegend) {
  const auto records = oracle_records(true);
  const std::string summary = results::make_markdown(records, "t");
  const size_t at = summary.find("Ranking by time:");
  ASSERT_NE(at, std::string::npos) << summary;
  const std::string md = summary.substr(at);
  EXPECT_NE(md.find("| 2 \u2248 | t5 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 1 | t1 |"), std::string::npos) << md;
  EXPECT_EQ(md.find("| none |"), std::string::npos) << md;  // not ranked
  for (const char* words : {"Mann\u2013Whitney U", "Holm-corrected over the 5 adjacent pairs",
                            "alpha 0.05", "timing.control.frame_ratio", "the control left out"})
    EXPECT_NE(md.find(words), std::string::npos) << words << "\n" << md;
  const std::string html = results::ranking_html(test::record_pointers(records));
  EXPECT_NE(
      html.find("<tr class=\"tie\"><td class=\"num\">2 \u2248</td><td class=\"name\">t5</td>"),
      std::string::npos)
      << html;
  EXPECT_NE(html.find("alpha 0.05"), std::string::npos) << html;
  // index.html holds it under the group's summary table.
  test::TempDir dir("rank_ties_html");
  results::write_html_report(records, (dir.path() / "run").string(), (dir.path() / "out").string(),
                             {}, "t", false);
  const std::string page = test::read_text(dir.path() / "out" / "index.html");
  EXPECT_NE(page.find(html), std::string::npos);
  // The paper's: LaTeX, the tie as $\approx$, the legend's signs as LaTeX.
  const std::string latex = results::ranking_latex(test::record_pointers(records));
  EXPECT_NE(latex.find("\n2 $\\approx$ & t5 & 1.19 & 30 & "), std::string::npos) << latex;
  const std::string legend = results::ranking_latex_legend(test::record_pointers(records));
  EXPECT_NE(legend.find("$\\approx$: not significantly different"), std::string::npos) << legend;
  EXPECT_NE(legend.find("Mann--Whitney U"), std::string::npos) << legend;
  EXPECT_EQ(legend.find("U+"), std::string::npos) << legend;
  // Without a control the legend says the frame times were ranked.
  const std::string plain = results::ranking_html(test::record_pointers(oracle_records(false)));
  EXPECT_NE(plain.find("timing.frame.samples_ms"), std::string::npos) << plain;
}

}  // namespace
}  // namespace sb
