// The HTML report as a person sees it: Debian's headless Chromium loads
// index.html from the file system (no network), runs its script, dumps the
// DOM and takes a screenshot. Fails on console messages or images that did
// not load; skipped where Chromium is not installed.
// (How the console is read: tests/common/chromium.h.)
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "../common/chromium.h"
#include "../metrics/test_util.h"
#include "report_fixture.h"

namespace sb {

using core::ImageF;
using test::BrowserRun;
using test::joined;
using test::run_chromium;
using test::shell_quote;

namespace {

namespace fs = std::filesystem;

using report_chromium = test::ChromiumTest;

TEST_F(report_chromium, PageLoadsEveryImageWithoutConsoleErrorsAndRenders) {
  test::TempDir dir("html_chromium");
  const auto run = test::make_synthetic_run(dir.path());
  test::write_synthetic_report(run);
  const fs::path index = run.out_dir / "index.html";

  const BrowserRun dom = run_chromium(chromium_, dir.path(), index, "--dump-dom");
  ASSERT_EQ(dom.exit_code, 0) << dom.log;
  ASSERT_NE(dom.dom.find("<body"), std::string::npos) << "no DOM dumped:\n" << dom.log;
  EXPECT_NE(dom.dom.find("data-images-ok=\"true\""), std::string::npos)
      << "images did not all load; the body tag says:\n"
      << dom.dom.substr(dom.dom.find("<body"), 400);
  EXPECT_TRUE(dom.console.empty()) << "console messages:\n" << joined(dom.console);
  // The script ran: the tables are sortable.
  EXPECT_NE(dom.dom.find("tabindex=\"0\""), std::string::npos);

  const fs::path shot = dir.path() / "report.png";
  const BrowserRun s =
      run_chromium(chromium_, dir.path(), index,
                   "--window-size=1280,2000 --screenshot=" + shell_quote(shot.string()));
  ASSERT_EQ(s.exit_code, 0) << s.log;
  EXPECT_TRUE(s.console.empty()) << "console messages:\n" << joined(s.console);
  ASSERT_TRUE(fs::is_regular_file(shot)) << s.log;
  EXPECT_GT(fs::file_size(shot), 20u * 1024u);
  const ImageF img = metrics::io::read_image(shot.string());
  EXPECT_EQ(img.width, 1280);
  EXPECT_EQ(img.height, 2000);
  // Not a blank page: many distinct colours (text, tables, images).
  std::set<uint32_t> colours;
  for (size_t p = 0; p < img.pixel_count(); p += 7) {
    uint32_t key = 0;
    for (int c = 0; c < 3; ++c)
      key = key * 256 + static_cast<uint32_t>(std::lround(img.data[p * img.channels + c] * 255.0f));
    colours.insert(key);
  }
  EXPECT_GT(colours.size(), 100u);
}

// A technique label "<!--<script>" in the viewer's JSON
// once put the HTML parser in its double-escaped script state: the rest of
// the page became script text, the page's scripts never ran and the Images
// section was empty. With '<' as \u003c the page is whole: its script ran
// (every image loaded and checked), and every viewer is in the DOM with its
// buttons, the label among them as text.
TEST_F(report_chromium, LabelThatOpensAScriptCommentLeavesThePageWhole) {
  test::TempDir dir("html_chromium_label");
  auto run = test::make_synthetic_run(dir.path());
  for (auto& r : run.records)
    if (r.technique_variant == "shadow_map/size=1024") r.technique_variant = "<!--<script>";
  test::write_synthetic_report(run);
  const fs::path index = run.out_dir / "index.html";

  const BrowserRun dom = run_chromium(chromium_, dir.path(), index, "--dump-dom");
  ASSERT_EQ(dom.exit_code, 0) << dom.log;
  EXPECT_TRUE(dom.console.empty()) << "console messages:\n" << joined(dom.console);
  EXPECT_NE(dom.dom.find("data-images-ok=\"true\""), std::string::npos)
      << "the page's script did not run:\n"
      << dom.dom.substr(0, 3000);
  const size_t images = dom.dom.find("<section id=\"images\">");
  ASSERT_NE(images, std::string::npos) << dom.dom.substr(0, 3000);
  const std::string section = dom.dom.substr(images);
  EXPECT_EQ(test::between(section, "<section class=\"viewer\"", ">").size(), 2u) << section;
  EXPECT_EQ(test::between(section, "&lt;!--&lt;script&gt;</button>", "<").size(), 2u) << section;
  // The viewers' script ran on them: none is still loading.
  EXPECT_EQ(section.find("data-state=\"loading\""), std::string::npos) << section.substr(0, 3000);
}

TEST_F(report_chromium, MissingImageIsDetected) {
  test::TempDir dir("html_chromium_missing");
  const auto run = test::make_synthetic_run(dir.path());
  test::write_synthetic_report(run);
  const std::string gone = *run.records[2].images.error_heatmap;
  ASSERT_TRUE(fs::remove(run.run_dir / gone));

  const BrowserRun dom =
      run_chromium(chromium_, dir.path(), run.out_dir / "index.html", "--dump-dom");
  ASSERT_EQ(dom.exit_code, 0) << dom.log;
  EXPECT_NE(dom.dom.find("data-images-ok=\"false\""), std::string::npos) << dom.dom.substr(0, 2000);
  const size_t missing = dom.dom.find("data-missing=\"");
  ASSERT_NE(missing, std::string::npos);
  EXPECT_NE(dom.dom.substr(missing, 400).find("pcf_box-k=3+size=1024/error.png"), std::string::npos)
      << dom.dom.substr(missing, 400);
  ASSERT_EQ(dom.console.size(), 1u) << joined(dom.console);
  EXPECT_NE(dom.console[0].find("missing image"), std::string::npos) << dom.console[0];
}

// Clicking a header sorts its table: a copy of the page with a script that
// clicks "rmse" (ascending), again (descending), "technique" and "frame_ms"
// (2.5, 12, 9, 120: text order would differ), writing each
// resulting order of the first table into the body's data attributes.
TEST_F(report_chromium, ClickingAHeaderSortsNumericallyAndToggles) {
  test::TempDir dir("html_chromium_sort");
  auto run = test::make_synthetic_run(dir.path());
  // A failed job shows no figure (docs/results.md, "Failed jobs carry no
  // numbers"): here the one that failed (vsm) is ok, so that its figures
  // (a tiny negative rmse, a 120 ms frame) are sorted too.
  for (record::JobRecord& r : run.records)
    if (r.status == record::JobStatus::Failed) {
      r.status = record::JobStatus::Ok;
      r.reason.reset();
    }
  test::write_synthetic_report(run);
  std::string html = test::read_text(run.out_dir / "index.html");
  const std::string probe = R"(<script>
window.addEventListener('load', function () {
  var table = document.querySelector('table.sortable');
  function header(name) {
    return Array.prototype.find.call(table.tHead.rows[0].cells,
                                     function (th) { return th.textContent === name; });
  }
  function order() {
    return Array.prototype.map.call(table.tBodies[0].rows,
                                    function (r) { return r.cells[0].textContent; }).join('|');
  }
  header('rmse').click();
  document.body.dataset.rmseAsc = order();
  header('rmse').click();
  document.body.dataset.rmseDesc = order();
  header('technique').click();
  document.body.dataset.techniqueAsc = order();
  header('frame_ms').click();
  document.body.dataset.frameAsc = order();
});
</script>
</body>)";
  const size_t end = html.rfind("</body>");
  ASSERT_NE(end, std::string::npos);
  html.replace(end, 7, probe);
  const fs::path page = run.out_dir / "sort_probe.html";
  {
    std::ofstream out(page, std::ios::binary);
    out << html;
  }
  const BrowserRun dom = run_chromium(chromium_, dir.path(), page, "--dump-dom");
  ASSERT_EQ(dom.exit_code, 0) << dom.log;
  EXPECT_TRUE(dom.console.empty()) << joined(dom.console);
  // rmse: vsm 0.00000 (rounded from a tiny negative), pcf 0.05, shadow_map
  // 0.10, none 0.15; the skipped job has no rmse and stays last both ways.
  const std::pair<const char*, const char*> expected[] = {
      {"rmse-asc",
       "vsm/k=9,prefilter=gauss|pcf_box/k=3,size=1024|shadow_map/size=1024|none|"
       "shadow_volume/mode=zpass"},
      {"rmse-desc",
       "none|shadow_map/size=1024|pcf_box/k=3,size=1024|vsm/k=9,prefilter=gauss|"
       "shadow_volume/mode=zpass"},
      {"technique-asc",
       "none|pcf_box/k=3,size=1024|shadow_map/size=1024|shadow_volume/mode=zpass|"
       "vsm/k=9,prefilter=gauss"},
      {"frame-asc",
       "none|pcf_box/k=3,size=1024|shadow_map/size=1024|vsm/k=9,prefilter=gauss|"
       "shadow_volume/mode=zpass"}};
  const std::string body = dom.dom.substr(dom.dom.find("<body"), 800);
  for (const auto& [attr, order] : expected)
    EXPECT_NE(body.find("data-" + std::string(attr) + "=\"" + order + "\""), std::string::npos)
        << attr << "\n"
        << body;
}

}  // namespace
}  // namespace sb
