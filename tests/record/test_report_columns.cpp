// One table of columns for results.csv, summary.md and the HTML report: the
// same headers in the same order (the CSV's with scene and resolution, which
// the others show as the heading of each table), and the same cells.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "../metrics/test_util.h"
#include "../report/report_fixture.h"
#include "results/html_report.h"
#include "results/report.h"
#include "results/report_columns.h"
#include "sample_records.h"

namespace sb {

using record::ClassesRecord;
using record::ControlTiming;
using record::JobRecord;
using record::JobStatus;
using record::MetricsRecord;
using record::ReferenceRecord;
using record::RegionStats;
using record::SecondReferenceRecord;
using record::Series;
using results::make_csv;
using results::make_markdown;
using results::reference_label;
using results::report_column;
using results::report_columns;
using results::write_html_report;

namespace {

std::vector<JobRecord> records() {
  JobRecord ok = test::identity_record("plates/layout=edge", "64x48", "pcf_box/k=3");
  ok.timing = test::coarse_timing({10, 12, 11}, {4, 5, 4.5});
  ControlTiming control;
  control.technique = "none";
  control.frame = Series::of({8, 8, 8});
  control.frame_ratio = Series::of({1.25, 1.5, 1.375});
  ok.timing->control = control;
  MetricsRecord m;
  m.visibility.geometry = RegionStats{};
  m.visibility.geometry->rmse = 0.0625;
  m.visibility.geometry->psnr = 24.08;
  m.visibility.all.rmse = 0.046875;  // with the sky: no table shows it
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

// The HTML report of `rs`, written into a fresh folder named `name`.
std::string html_report_of(const std::vector<JobRecord>& rs, const std::string& name) {
  test::TempDir dir(name);
  write_html_report(rs, dir.path().string(), dir.file("report"), {}, "title");
  return test::read_text(dir.path() / "report" / "index.html");
}

// The headers of the HTML report's first summary table.
std::vector<std::string> first_table_headers(const std::string& html) {
  std::vector<std::string> ths;
  for (const auto& th :
       test::between(test::between(html, "<thead>", "</thead>").at(0), "<th", "</th>"))
    ths.push_back(th.substr(th.find('>') + 1));
  return ths;
}

// Every column's header; without the group's columns, and without the
// optional ones (the sample records have no second reference).
std::vector<std::string> headers(bool with_group_columns) {
  std::vector<std::string> out;
  for (const auto& c : report_columns())
    if (with_group_columns || (!c.per_group && !c.optional)) out.push_back(c.header);
  return out;
}

// The records measured against an exact reference and, second, a Monte
// Carlo one: penumbra RMSE 0.1 against the exact, 0.125 against Monte Carlo.
std::vector<JobRecord> records_with_second_reference() {
  std::vector<JobRecord> rs = records();
  ReferenceRecord exact, mc;
  exact.method = "exact_clipper";
  mc.method = "embree_stratified_packet16";
  mc.spp = 256;
  rs[0].reference = exact;
  rs[0].metrics->visibility.penumbra.rmse = 0.1;
  SecondReferenceRecord second;
  second.reference = mc;
  second.visibility.geometry = RegionStats{};
  second.visibility.geometry->rmse = 0.0675;
  second.visibility.all.rmse = 0.05;
  second.visibility.penumbra.rmse = 0.125;
  rs[0].second_reference = second;
  rs[1].reference = exact;
  return rs;
}

TEST(ReportColumns, SameHeadersInCsvMarkdownAndHtml) {
  const std::vector<std::string> all = headers(true), shown = headers(false);
  EXPECT_EQ(all.front(), "scene");
  EXPECT_EQ(all.back(), "reason");
  // Scene and resolution head each table instead; the median's interval and
  // the noisy mark, the GPU memory's, FLIP's, the terminator's, the distance
  // thirds', the classes' and the second reference's columns are there only
  // when a record has them.
  EXPECT_EQ(all.size(), shown.size() + 2 + 2 + 1 + 1 + 1 + 3 + 2 + 3);

  const std::string csv = make_csv(records());
  EXPECT_EQ(csv.substr(0, csv.find('\n')), join(all, ","));

  const std::string md = make_markdown(records(), "title");
  EXPECT_NE(md.find("## plates/layout=edge @ 64x48\n\n| " + join(shown, " | ") + " |\n"),
            std::string::npos)
      << md;

  EXPECT_EQ(first_table_headers(html_report_of(records(), "report_columns")), shown);
}

TEST(ReportColumns, CellsAgreeAcrossTheTables) {
  const auto rs = records();
  const std::string csv = make_csv(rs);
  const std::string md = make_markdown(rs, "title");
  const std::string html = html_report_of(rs, "report_cells");
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
  EXPECT_NE(csv.find(",skipped,,,,,,,,,,,,,,,,,,,,,,,,casters are not closed\n"), std::string::npos)
      << csv;
  EXPECT_THROW(report_column("nonsense"), std::out_of_range);
}

TEST(ReportColumns, ErrorColumnsAreTheGeometryRegionsAndOlderRecordsLeaveThemEmpty) {
  auto rs = records();
  RegionStats& g = *rs[0].metrics->visibility.geometry;
  g.mae = 0.03125;
  g.max_error = 0.5;
  g.ssim = 0.875;
  g.frac_over_005 = 0.25;
  RegionStats& all = rs[0].metrics->visibility.all;  // sky included: other numbers
  all.mae = all.max_error = all.ssim = all.frac_over_005 = all.psnr = 0.75;
  EXPECT_EQ(report_column("rmse").cell(rs[0]), "0.06250");
  EXPECT_EQ(report_column("mae").cell(rs[0]), "0.03125");
  EXPECT_EQ(report_column("max_error").cell(rs[0]), "0.5000");
  EXPECT_EQ(report_column("psnr").cell(rs[0]), "24.08");
  EXPECT_EQ(report_column("ssim").cell(rs[0]), "0.8750");
  EXPECT_EQ(report_column("frac_over_0.05").cell(rs[0]), "0.2500");
  // A record written before the region existed: empty cells, not `all`'s.
  rs[0].metrics->visibility.geometry.reset();
  for (const char* name : {"rmse", "mae", "max_error", "psnr", "ssim", "frac_over_0.05"})
    EXPECT_EQ(report_column(name).cell(rs[0]), "") << name;
}

TEST(ReportColumns, PenumbraMissedAndInventedComeFromTheRecordsClasses) {
  auto rs = records();
  EXPECT_EQ(report_column("penumbra_missed").cell(rs[0]), "");  // an older record: no classes
  rs[0].classes = ClassesRecord{};
  rs[0].classes->counts = {{{90, 10, 0}, {30, 50, 20}, {0, 0, 100}}};
  EXPECT_EQ(report_column("penumbra_missed").cell(rs[0]), "0.500");
  EXPECT_EQ(report_column("penumbra_invented").cell(rs[0]), "0.167");
  const std::string md = make_markdown(rs, "title");
  EXPECT_NE(md.find("| penumbra_missed | penumbra_invented |"), std::string::npos) << md;
}

TEST(ReportColumns, SecondReferenceColumnsAppearOnlyWhenARecordHasOne) {
  const auto rs = records_with_second_reference();
  // (0.125² - 0.1²) / 0.125²: the Monte Carlo reference's noise explains 36%
  // of the penumbra MSE against it.
  EXPECT_EQ(report_column("mc_noise_share").cell(rs[0]), "0.360");
  EXPECT_EQ(report_column("second_rmse").cell(rs[0]), "0.06750");
  EXPECT_EQ(report_column("second_penumbra_rmse").cell(rs[0]), "0.12500");
  EXPECT_EQ(report_column("second_rmse").cell(rs[1]), "");

  std::vector<std::string> shown = headers(false);
  shown.insert(shown.end() - 1, {"second_rmse", "second_penumbra_rmse", "mc_noise_share"});
  const std::string md = make_markdown(rs, "title");
  EXPECT_NE(md.find("| " + join(shown, " | ") + " |\n"), std::string::npos) << md;
  EXPECT_NE(md.find("| 0.06750 | 0.12500 | 0.360 |"), std::string::npos) << md;
  // Both references are named, the first as exact.
  EXPECT_NE(md.find("reference: exact (exact_clipper)"), std::string::npos) << md;
  EXPECT_NE(md.find("second reference: Monte Carlo, 256 spp"), std::string::npos) << md;

  const std::string html = html_report_of(rs, "report_second");
  EXPECT_EQ(first_table_headers(html), shown);
  EXPECT_NE(html.find("<td class=\"num\">0.360</td>"), std::string::npos);
}

TEST(ReportColumns, GpuMemoryIsTheTotalInMibAndAppearsOnlyWhenARecordHasIt) {
  auto rs = records();
  EXPECT_EQ(report_column("gpu_mib").cell(rs[0]), "");
  EXPECT_EQ(make_markdown(rs, "title").find("gpu_mib"), std::string::npos);
  // A record from before the needs were counted: its gpu_bytes is not the
  // total, and no cell shows it as one.
  rs[0].technique.gpu_bytes = 20971520;
  EXPECT_EQ(report_column("gpu_mib").cell(rs[0]), "");
  EXPECT_EQ(make_markdown(rs, "title").find("gpu_mib"), std::string::npos);
  // The technique's own 20 MiB and the 0.5 MiB the harness holds for its needs.
  rs[0].technique.set_gpu_bytes(20971520,
                                {{"edge_adjacency", 393216}, {"silhouette_edges", 131072}});
  EXPECT_EQ(report_column("gpu_mib").cell(rs[0]), "20.50");
  std::vector<std::string> shown = headers(false);
  shown.insert(std::find(shown.begin(), shown.end(), "x_control") + 1, "gpu_mib");
  const std::string md = make_markdown(rs, "title");
  EXPECT_NE(md.find("| " + join(shown, " | ") + " |\n"), std::string::npos) << md;
  EXPECT_NE(md.find("| 20.50 |"), std::string::npos) << md;
}

// A failed job shows its status and reason only, even from a record that
// keeps figures where an ok one has them (one made in memory, or read
// whole by an older build): every figure cell is empty.
TEST(ReportColumns, AFailedJobsFigureCellsAreEmptyWhateverItsRecordHolds) {
  auto rs = records();
  JobRecord failed = rs[0];
  failed.technique_variant = "writes_nan";
  failed.technique.gpu_bytes = 1 << 20;
  failed.status = JobStatus::Failed;
  failed.reason = "visibility outside [0,1]: 7 NaN/Inf, 0 below 0, 0 above 1 (tolerance 1e-5)";
  int figures = 0;
  for (const auto& c : report_columns()) {
    if (!c.numeric()) continue;
    figures += !c.cell(rs[0]).empty();
    EXPECT_EQ(c.cell(failed), "") << c.name;
  }
  EXPECT_GE(figures, 6);  // the same record, ok, has them
  EXPECT_EQ(report_column("status").cell(failed), "failed");
  EXPECT_EQ(report_column("reason").cell(failed), *failed.reason);
  rs.push_back(failed);
  const std::string csv = make_csv(rs);
  // Every cell between the status and the reason is empty.
  size_t status_at = 0, reason_at = 0;
  for (size_t i = 0; i < report_columns().size(); ++i) {
    if (std::string(report_columns()[i].name) == "status") status_at = i;
    if (std::string(report_columns()[i].name) == "reason") reason_at = i;
  }
  ASSERT_GT(reason_at, status_at + 6);
  EXPECT_NE(csv.find(",writes_nan,failed" + std::string(reason_at - status_at, ',') +
                     "\"visibility outside"),
            std::string::npos)
      << csv;
}

TEST(ReportColumns, FlipIsTheShadedImagesWholeImageFlipAndAppearsOnlyWhenMeasured) {
  auto rs = records();
  EXPECT_EQ(report_column("flip").cell(rs[0]), "");
  EXPECT_EQ(make_markdown(rs, "title").find("flip"), std::string::npos);
  rs[0].metrics->shaded.geometry = RegionStats{};
  rs[0].metrics->shaded.geometry->flip_mean = 0.125;     // not a region's
  rs[0].metrics->shaded.all.flip_mean = 0.5;             // nor this one
  rs[0].metrics->visibility.geometry->flip_mean = 0.25;  // nor V's
  EXPECT_EQ(report_column("flip").cell(rs[0]), "");      // a record from before it
  rs[0].metrics->flip_shaded = 0.0625;
  EXPECT_EQ(report_column("flip").cell(rs[0]), "0.0625");
  EXPECT_EQ(report_column("flip").cell(rs[1]), "");  // skipped: no metrics
  std::vector<std::string> shown = headers(false);
  shown.insert(std::find(shown.begin(), shown.end(), "frac_over_0.05") + 1, "flip");
  const std::string md = make_markdown(rs, "title");
  EXPECT_NE(md.find("| " + join(shown, " | ") + " |\n"), std::string::npos) << md;
  EXPECT_NE(md.find("| 0.0625 |"), std::string::npos) << md;
}

TEST(ReportColumns, TerminatorRmseIsTheVisibilitysTerminatorRegionAndAppearsOnlyWithIt) {
  auto rs = records();
  EXPECT_EQ(report_column("terminator_rmse").cell(rs[0]), "");
  EXPECT_EQ(make_markdown(rs, "title").find("terminator_rmse"), std::string::npos);
  rs[0].metrics->visibility.terminator = RegionStats{};
  rs[0].metrics->visibility.terminator->rmse = 0.25;
  rs[0].metrics->shaded.terminator = RegionStats{};
  rs[0].metrics->shaded.terminator->rmse = 0.5;  // not the shaded image's
  EXPECT_EQ(report_column("terminator_rmse").cell(rs[0]), "0.25000");
  std::vector<std::string> shown = headers(false);
  shown.insert(std::find(shown.begin(), shown.end(), "penumbra_rmse") + 1, "terminator_rmse");
  const std::string md = make_markdown(rs, "title");
  EXPECT_NE(md.find("| " + join(shown, " | ") + " |\n"), std::string::npos) << md;
  EXPECT_NE(md.find("| 0.25000 |"), std::string::npos) << md;
}

TEST(ReportColumns, DistanceThirdColumnsAreTheVisibilitysThirdsAndAppearOnlyWithThem) {
  auto rs = records();
  EXPECT_EQ(report_column("near_rmse").cell(rs[0]), "");
  rs[0].metrics->visibility.near_third = RegionStats{};
  rs[0].metrics->visibility.near_third->rmse = 0.25;
  rs[0].metrics->visibility.middle_third = RegionStats{};
  rs[0].metrics->visibility.middle_third->rmse = 0.125;
  rs[0].metrics->visibility.far_third = RegionStats{};
  rs[0].metrics->visibility.far_third->rmse = 0.0625;
  EXPECT_EQ(report_column("near_rmse").cell(rs[0]), "0.25000");
  EXPECT_EQ(report_column("middle_rmse").cell(rs[0]), "0.12500");
  EXPECT_EQ(report_column("far_rmse").cell(rs[0]), "0.06250");
  EXPECT_EQ(report_column("near_rmse").cell(rs[1]), "");  // skipped: no metrics

  std::vector<std::string> shown = headers(false);
  shown.insert(shown.end() - 1, {"near_rmse", "middle_rmse", "far_rmse"});
  const std::string md = make_markdown(rs, "title");
  EXPECT_NE(md.find("| " + join(shown, " | ") + " |\n"), std::string::npos) << md;
  EXPECT_NE(md.find("| 0.25000 | 0.12500 | 0.06250 |"), std::string::npos) << md;
}

TEST(ReportColumns, NoiseShareNeedsOneExactAndOneMonteCarloReference) {
  auto rs = records_with_second_reference();
  // Swapped, Monte Carlo first: the same share.
  std::swap(*rs[0].reference, rs[0].second_reference->reference);
  rs[0].metrics->visibility.penumbra.rmse = 0.125;
  rs[0].second_reference->visibility.penumbra.rmse = 0.1;
  EXPECT_EQ(report_column("mc_noise_share").cell(rs[0]), "0.360");
  // An exact reference that fell back to Monte Carlo: two Monte Carlo ones.
  rs[0].second_reference->reference.method = rs[0].reference->method;
  rs[0].second_reference->reference.exact_fallback = "alpha-masked casters";
  EXPECT_EQ(report_column("mc_noise_share").cell(rs[0]), "");
  EXPECT_NE(reference_label(rs[0].second_reference->reference).find("not exact: alpha-masked"),
            std::string::npos);
}

// summary.md writes fields a record holds, and a record
// may come from anyone. Every character that opens markup in CommonMark
// (code, links, images, HTML, entities) must reach the file escaped (an odd
// number of backslashes before it), and no control character but the line
// ends may reach it.
TEST(ReportColumns, SummaryEscapesEveryFieldFromARecord) {
  auto rs = records();
  for (auto& r : rs) {
    r.backend = "osmesa` <img src=x onerror=alert(1)> [link](http://example.com) `";
    r.gl_renderer = "llvmpipe`<b>bold</b>`&amp;";
    r.timing_source = "gl_timer_query` ![i](x.png)";
  }
  rs[1].reason = "casters \x1b]0;title\x07\x1b[2J are not [closed](http://example.com) |";
  rs[1].technique_variant = "shadow_volume/<!--<script>";
  const std::string md = make_markdown(rs, "title");
  for (size_t i = 0; i < md.size(); ++i) {
    const char c = md[i];
    EXPECT_TRUE(c == '\n' || static_cast<unsigned char>(c) >= 0x20) << "byte " << i << ":\n" << md;
    if (std::string_view("`<>[]&").find(c) == std::string_view::npos) continue;
    size_t slashes = 0;
    while (slashes < i && md[i - 1 - slashes] == '\\') ++slashes;
    EXPECT_EQ(slashes % 2, 1u) << "unescaped '" << c << "' at byte " << i << ": "
                               << md.substr(i < 40 ? 0 : i - 40, 80);
  }
  EXPECT_NE(md.find("osmesa"), std::string::npos) << md;
}

}  // namespace
}  // namespace sb
