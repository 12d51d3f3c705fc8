// Noisy jobs said out loud (results/noisy_jobs.h): a record judged noisy is
// marked in results.csv, summary.md, the HTML report and the LaTeX tables,
// with a legend naming the threshold; the console's line says "noisy ±x %";
// the run's last line counts them and gives the load. Records built as the
// runner builds them, their noise judged from given samples.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../common/text.h"
#include "../metrics/test_util.h"
#include "../report/report_fixture.h"
#include "results/html_report.h"
#include "results/latex_tables.h"
#include "results/noisy_jobs.h"
#include "results/report.h"
#include "results/report_columns.h"
#include "run/job_line.h"
#include "sample_records.h"

namespace sb {

using record::JobRecord;
using record::MetricsRecord;
using record::NoiseRecord;
using record::RegionStats;
using results::is_noisy;
using results::kNoisyMark;
using results::make_csv;
using results::make_markdown;
using results::noise_warning;
using results::report_column;

namespace {

// An ok job whose frames spread ±`spread` ms around 10, judged against 5 %,
// timed at loads `start` and `end` on 2 cores.
JobRecord job(const std::string& technique, double spread, double start = 1.0, double end = 1.0) {
  JobRecord r = test::identity_record("sphere_grid", "64x48", technique);
  r.timing = test::coarse_timing(test::spread_frames(spread), test::spread_frames(spread / 2));
  NoiseRecord n = NoiseRecord::judge(*r.timing, 0.05);
  n.load_average_start = start;
  n.load_average_end = end;
  n.usable_cores = 2;
  r.timing->noise = n;
  MetricsRecord m;
  m.visibility.geometry = RegionStats{};
  m.visibility.geometry->rmse = 0.0625;
  r.metrics = m;
  return r;
}

std::vector<JobRecord> one_noisy() {
  // ±30 % spread: half-width (11.2 - 8.5) / 2 / 9.85 = 13.7 %; ±2 %: 0.9 %.
  return {job("pcf_box/k=3", 3.0, 1.5, 3.25), job("pcss", 0.2, 0.75, 1.0)};
}

// The line of `text` that holds `needle`, or "".
std::string line_with(const std::string& text, const std::string& needle) {
  const size_t at = text.find(needle);
  if (at == std::string::npos) return "";
  const size_t from = text.rfind('\n', at) + 1;
  return text.substr(from, text.find('\n', at) - from);
}

TEST(NoisyJobs, TheJudgementIsTheRecordsAndOnlyForOkJobs) {
  const auto rs = one_noisy();
  EXPECT_TRUE(is_noisy(rs[0]));
  EXPECT_FALSE(is_noisy(rs[1]));
  JobRecord failed = rs[0];
  failed.status = record::JobStatus::Failed;
  EXPECT_FALSE(is_noisy(failed));
  JobRecord older = rs[0];
  older.timing->noise.reset();  // written before timing.noise
  EXPECT_FALSE(is_noisy(older));
}

TEST(NoisyJobs, TheConsoleLineSaysNoisyAndTheInterval) {
  const auto rs = one_noisy();
  const std::string line = run::job_line(rs[0], 1, 2);
  EXPECT_NE(line.find("  noisy ±13.7 %"), std::string::npos) << line;
  EXPECT_EQ(run::job_line(rs[1], 2, 2).find("noisy"), std::string::npos);
}

TEST(NoisyJobs, CsvHasTheIntervalAndTheMark) {
  const std::string csv = make_csv(one_noisy());
  EXPECT_NE(csv.find(",time_ci,noisy,"), std::string::npos) << csv;
  EXPECT_NE(line_with(csv, "pcf_box").find(",0.137," + std::string(kNoisyMark) + ","),
            std::string::npos)
      << csv;
  EXPECT_EQ(line_with(csv, "pcss").find(kNoisyMark), std::string::npos) << csv;
  EXPECT_EQ(report_column("time_ci").cell(one_noisy()[1]), "0.009");
}

TEST(NoisyJobs, MarkdownMarksTheNoisyRowAndSaysWhyUnderTheTable) {
  const std::string md = make_markdown(one_noisy(), "t");
  EXPECT_NE(line_with(md, "| pcf_box/k=3 |").find(kNoisyMark), std::string::npos) << md;
  EXPECT_EQ(line_with(md, "| pcss |").find(kNoisyMark), std::string::npos) << md;
  const std::string legend = line_with(md, std::string(kNoisyMark) + " noisy:");
  EXPECT_NE(legend.find("wider than ±5 % (frames.noise_threshold)"), std::string::npos) << md;
  // Nothing noisy: no mark, no column, no legend.
  const std::string quiet = make_markdown({one_noisy()[1]}, "t");
  EXPECT_EQ(quiet.find(kNoisyMark), std::string::npos) << quiet;
  EXPECT_EQ(quiet.find("| noisy |"), std::string::npos) << quiet;
}

TEST(NoisyJobs, HtmlMarksTheNoisyRowAndSaysWhyUnderTheTable) {
  test::TempDir dir("noisy_html");
  results::write_html_report(one_noisy(), dir.path().string(), dir.file("report"), {}, "t");
  const std::string html = test::read_text(dir.path() / "report" / "index.html");
  const std::string row = test::between(html, "<tr><td class=\"name\">pcf_box/k=3", "</tr>").at(0);
  EXPECT_NE(row.find(kNoisyMark), std::string::npos) << row;
  EXPECT_NE(html.find(std::string("<p class=\"note noisy\">") + kNoisyMark +
                      " noisy: the median&#39;s 95 % interval"),
            std::string::npos)
      << html;
}

TEST(NoisyJobs, LatexMarksTheNoisyTechniqueAndAddsALegendRow) {
  const auto rs = one_noisy();
  const std::vector<const JobRecord*> group{&rs[0], &rs[1]};
  const auto columns = results::latex_columns({"frame_ms"}, rs);
  const std::string tex = results::make_latex_table(group, columns);
  EXPECT_NE(tex.find("pcf\\_box/k=3\\textsuperscript{\\dag} &"), std::string::npos) << tex;
  EXPECT_NE(tex.find("pcss &"), std::string::npos) << tex;
  EXPECT_NE(tex.find("\\multicolumn{2}{l}{\\footnotesize\\dag{} noisy: the median's 95\\,\\% "
                     "interval is wider than $\\pm$5\\,\\%} \\\\\n\\end{tabular}"),
            std::string::npos)
      << tex;
  const std::vector<const JobRecord*> quiet{&rs[1]};
  EXPECT_EQ(results::make_latex_table(quiet, columns).find("dag"), std::string::npos);
}

TEST(NoisyJobs, TheRunsLastLineCountsThemAndGivesTheLoad) {
  std::vector<JobRecord> rs = one_noisy();
  rs.push_back(job("vsm", 3.0, 2.0, 2.5));
  JobRecord skipped =
      test::identity_record("sphere_grid", "64x48", "shadow_volume", record::JobStatus::Skipped);
  rs.push_back(skipped);
  EXPECT_EQ(noise_warning(rs),
            "warning: 2 of 3 timed jobs were noisy (the median's 95 % interval wider than ±5 %); "
            "the load average was 0.8–3.2 on 2 cores");
  EXPECT_EQ(noise_warning({one_noisy()[1]}), std::nullopt);
}

}  // namespace

}  // namespace sb
