// The HTML report's content, without a browser: every variant, escaped
// record strings, image links that resolve on disk from the report folder
// (inside or outside the run directory), nothing fetched from a network, and
// a legend drawn with the heat maps' own colour ramp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../metrics/test_util.h"
#include "report_fixture.h"
#include "results/html_page.h"
#include "results/html_report.h"
#include "results/report.h"

namespace sb {

using core::ImageF;
using results::html_escape;
using results::kHeatmapLegendFile;
using results::make_csv;
using results::write_html_report;

namespace {

namespace fs = std::filesystem;

std::string percent_decode(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size()) {
      out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

// Every value of attribute `attr` ("src" or "href") in the page.
std::vector<std::string> attribute_values(const std::string& html, const std::string& attr) {
  return test::between(html, " " + attr + "=\"", "\"");
}

void expect_links_resolve(const test::SyntheticRun& run, const std::string& html) {
  const auto srcs = attribute_values(html, "src");
  // 2 groups x (reference + 4 jobs with images x 2) + 2 legends + 1 chart.
  EXPECT_EQ(srcs.size(), 2u * (1 + 4 * 2) + 2 + 1);
  for (const auto& src : srcs) {
    EXPECT_EQ(src.find("://"), std::string::npos) << src;
    EXPECT_NE(src.front(), '/') << "not relative: " << src;
    EXPECT_TRUE(fs::is_regular_file(run.out_dir / percent_decode(src))) << src;
  }
  for (const auto& href : attribute_values(html, "href")) {
    if (href.front() == '#') continue;
    EXPECT_EQ(href.find("://"), std::string::npos) << href;
    EXPECT_TRUE(fs::exists(run.out_dir / percent_decode(href))) << href;
  }
}

TEST(report_html, ContainsVariantsEscapedStringsAndResolvableImages) {
  test::TempDir dir("html_report");
  const auto run = test::make_synthetic_run(dir.path());
  test::write_synthetic_report(run);
  const fs::path index = run.out_dir / "index.html";
  ASSERT_TRUE(fs::is_regular_file(index));
  const std::string html = test::read_text(index);

  for (const auto& r : run.records)
    EXPECT_NE(html.find(r.technique_variant), std::string::npos) << r.technique_variant;
  EXPECT_NE(html.find("plates/layout=edge @ 64x48"), std::string::npos);
  EXPECT_NE(html.find("plates/layout=edge @ 96x72"), std::string::npos);
  // The failed job's reason, escaped, in the table and on its card; never raw.
  const std::string escaped =
      "GL error &lt;GL_INVALID_ENUM&gt; &amp; &quot;bad&quot; &#39;enum&#39;";
  size_t count = 0;
  for (size_t p = html.find(escaped); p != std::string::npos; p = html.find(escaped, p + 1))
    ++count;
  EXPECT_EQ(count, 4u);  // table + card, in each of the two groups
  EXPECT_EQ(html.find(test::kNastyReason), std::string::npos);
  EXPECT_EQ(html.find("<GL_INVALID_ENUM>"), std::string::npos);
  EXPECT_NE(html.find("llvmpipe &lt;test&gt;"), std::string::npos);
  EXPECT_NE(html.find("<title>synthetic &lt;report&gt; &amp; co</title>"), std::string::npos);
  EXPECT_NE(html.find("Error against frame time &lt;all&gt;"), std::string::npos);
  EXPECT_NE(html.find("casters are not closed"), std::string::npos);

  // Offline: no network reference and no external script or style sheet.
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("<script src"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("@import"), std::string::npos);

  expect_links_resolve(run, html);
  // Written atomically: no temporary file left behind.
  for (const auto& e : fs::directory_iterator(run.out_dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST(report_html, TableCellsAreTheCsvCellsAndSortable) {
  test::TempDir dir("html_table");
  const auto run = test::make_synthetic_run(dir.path());
  test::write_synthetic_report(run);
  const std::string html = test::read_text(run.out_dir / "index.html");
  EXPECT_NE(html.find("<table class=\"sortable\">"), std::string::npos);
  // The same columns as summary.md (results/report_columns.h).
  std::string headers;
  const std::string first_head = test::between(html, "<thead>", "</thead>").at(0);
  for (const auto& th : test::between(first_head, "<th", "</th>"))
    headers += th.substr(th.find('>') + 1) + ",";
  EXPECT_EQ(headers,
            "technique,status,frame_ms,technique_ms,x_control,rmse,mae,max_error,psnr,ssim,"
            "frac_over_0.05,"
            "penumbra_rmse,reason,");
  // Numbers formatted as in results.csv ("inf" for an infinite PSNR).
  const std::string csv = make_csv(run.records);
  EXPECT_NE(csv.find(",0.15000,"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num\">0.15000</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num\">inf</td>"), std::string::npos);
  EXPECT_NE(html.find("aria-sort"), std::string::npos);  // the sorting script
  EXPECT_NE(html.find("dataset.imagesOk"), std::string::npos);
}

TEST(report_html, ReportInsideTheRunDirectoryLinksRelatively) {
  test::TempDir dir("html_inside");
  const auto run = test::make_synthetic_run(dir.path(), dir.path() / "run" / "report");
  test::write_synthetic_report(run);
  const std::string html = test::read_text(run.out_dir / "index.html");
  EXPECT_NE(html.find("src=\"../reference/plates--layout=edge__64x48/shaded.png\""),
            std::string::npos);
  EXPECT_NE(
      html.find("src=\"../jobs/plates--layout=edge__64x48__pcf_box-k=3+size=1024/error.png\""),
      std::string::npos);
  expect_links_resolve(run, html);
}

TEST(report_html, LegendIsTheHeatMapRamp) {
  test::TempDir dir("html_legend");
  const auto run = test::make_synthetic_run(dir.path());
  test::write_synthetic_report(run);
  const ImageF legend = metrics::io::read_image((run.out_dir / kHeatmapLegendFile).string());
  ASSERT_EQ(legend.channels, 3);
  ASSERT_GT(legend.width, 255);
  for (int x = 0; x < legend.width; ++x) {
    float rgb[3];
    metrics::heatmap_colour(static_cast<float>(x) / static_cast<float>(legend.width - 1), rgb);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(legend.at(x, 0, c), rgb[c], 0.5f / 255 + 1e-6f) << x;
      EXPECT_EQ(legend.at(x, legend.height - 1, c), legend.at(x, 0, c));
    }
  }
  // Its ticks run from 0 to the records' full scale.
  const std::string html = test::read_text(run.out_dir / "index.html");
  EXPECT_NE(html.find("<span>0</span><span>0.0625</span><span>0.125</span><span>0.1875</span>"
                      "<span>&ge; 0.25</span>"),
            std::string::npos);
}

TEST(report_html, NoRecordsStillMakesAPage) {
  test::TempDir dir("html_empty");
  fs::create_directories(dir.path() / "run");
  write_html_report({}, (dir.path() / "run").string(), (dir.path() / "out").string(), {}, "empty");
  const std::string html = test::read_text(dir.path() / "out" / "index.html");
  EXPECT_NE(html.find("0 jobs"), std::string::npos);
  EXPECT_NE(html.find("No charts."), std::string::npos);
  EXPECT_NE(html.find("</html>"), std::string::npos);
}

TEST(report_html, EscapesAllSpecialCharacters) {
  EXPECT_EQ(html_escape("a<b>&\"c'"), "a&lt;b&gt;&amp;&quot;c&#39;");
  EXPECT_EQ(html_escape("plain"), "plain");
}

}  // namespace
}  // namespace sb
