// One table of columns for results.csv, summary.md and the HTML report: the
// same headers in the same order (the CSV's with scene and resolution, which
// the others show as the heading of each table), and the same cells.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../metrics/test_util.h"
#include "../report/report_fixture.h"
#include "results/html_report.h"
#include "results/report.h"
#include "results/report_columns.h"
#include "sample_records.h"

namespace sb {
namespace {

std::vector<JobRecord> records() {
  JobRecord ok = test::identity_record("plates/layout=edge", "64x48", "pcf_box/k=3");
  ok.timing = test::coarse_timing({10, 12, 11}, {4, 5, 4.5});
  ControlTiming control;
  control.technique = "none";
  control.frame = TimingSeries::of({8, 8, 8});
  control.frame_ratio = RatioSeries::of({1.25, 1.5, 1.375});
  ok.timing->control = control;
  MetricsRecord m;
  m.visibility.all.rmse = 0.0625;
  m.visibility.all.psnr = 24.08;
  m.visibility.penumbra.rmse = 0.125;
  ok.metrics = m;
  JobRecord skipped =
      test::identity_record("plates/layout=edge", "64x48", "shadow_volume", JobStatus::Skipped);
  skipped.reason = "casters are not closed";
  return {ok, skipped};
}

std::string join(const std::vector<std::string>& parts, const std::string& sep) {
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i ? sep : "") + parts[i];
  return out;
}

std::vector<std::string> headers(bool with_group_columns) {
  std::vector<std::string> out;
  for (const auto& c : report_columns())
    if (with_group_columns || !c.per_group) out.push_back(c.header);
  return out;
}

TEST(ReportColumns, SameHeadersInCsvMarkdownAndHtml) {
  const std::vector<std::string> all = headers(true), shown = headers(false);
  EXPECT_EQ(all.front(), "scene");
  EXPECT_EQ(all.back(), "reason");
  EXPECT_EQ(all.size(), shown.size() + 2);  // scene and resolution head each table instead

  const std::string csv = make_csv(records());
  EXPECT_EQ(csv.substr(0, csv.find('\n')), join(all, ","));

  const std::string md = make_markdown(records(), "title");
  EXPECT_NE(md.find("## plates/layout=edge @ 64x48\n\n| " + join(shown, " | ") + " |\n"),
            std::string::npos)
      << md;

  test::TempDir dir("report_columns");
  write_html_report(records(), dir.path().string(), dir.file("report"), {}, "title");
  const std::string html = test::read_text(dir.path() / "report" / "index.html");
  std::vector<std::string> ths;
  for (const auto& th :
       test::between(test::between(html, "<thead>", "</thead>").at(0), "<th", "</th>"))
    ths.push_back(th.substr(th.find('>') + 1));
  EXPECT_EQ(ths, shown);
}

TEST(ReportColumns, CellsAgreeAcrossTheTables) {
  const auto rs = records();
  const std::string csv = make_csv(rs);
  const std::string md = make_markdown(rs, "title");
  test::TempDir dir("report_cells");
  write_html_report(rs, dir.path().string(), dir.file("report"), {}, "title");
  const std::string html = test::read_text(dir.path() / "report" / "index.html");
  // The ratio to the control is the median of the per-frame ratios.
  EXPECT_EQ(report_column("x_control").cell(rs[0]), "1.375");
  for (const char* name : {"frame_ms", "x_control", "rmse", "psnr", "penumbra_rmse"}) {
    const std::string cell = report_column(name).cell(rs[0]);
    ASSERT_FALSE(cell.empty()) << name;
    EXPECT_NE(csv.find("," + cell + ","), std::string::npos) << name << ": " << cell;
    EXPECT_NE(md.find("| " + cell + " |"), std::string::npos) << name << ": " << cell;
    EXPECT_NE(html.find("<td class=\"num\">" + cell + "</td>"), std::string::npos) << name;
  }
  // A skipped job has no figures: empty cells, and its reason in the last column.
  EXPECT_EQ(report_column("rmse").cell(rs[1]), "");
  EXPECT_EQ(report_column("reason").cell(rs[1]), "casters are not closed");
  EXPECT_NE(csv.find(",skipped,,,,,,,,,,,casters are not closed\n"), std::string::npos) << csv;
  EXPECT_THROW(report_column("nonsense"), std::out_of_range);
}

}  // namespace
}  // namespace sb
