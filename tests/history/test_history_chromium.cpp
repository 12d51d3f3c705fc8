// The history's site as a person sees it: Debian's headless Chromium loads
// index.html and a series page from the file system (no network), runs
// their script and dumps the DOM. Fails on console messages or images that
// did not load; skipped where Chromium is not installed (scripts/test.sh
// installs it).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <string>

#include "../common/chromium.h"
#include "../common/text.h"
#include "core/image.h"
#include "history/history_db.h"
#include "history/history_report.h"
#include "history_fixture.h"
#include "metrics/image_io.h"

namespace sb::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using history_chromium = ChromiumTest;

// Eight runs, one job 40 % slower from the fifth, its images in the runs
// on both sides of the step.
history::HistoryReport make_site(const fs::path& dir, std::string* slowed_job) {
  const json::json_pointer ratio("/timing/control/frame_ratio/median");
  *slowed_job = jsonl_records(kCiBaseline).at(1)["job_id"];
  history::HistoryDb db((dir / "h.sqlite").string());
  std::mt19937_64 rng(3);
  std::normal_distribution<double> z(0.0, 1.0);
  for (int run = 0; run < 8; ++run) {
    const fs::path folder = run_folder(dir, "run" + std::to_string(run), [&](json& j) {
      start_on_day(j, run + 1);
      if (!j.contains(ratio)) return;
      j[ratio] = j[ratio].get<double>() * std::exp(0.02 * z(rng)) *
                 (j["job_id"] == *slowed_job && run >= 4 ? 1.4 : 1.0);
    });
    core::ImageF img(32, 24, 3);
    for (std::size_t i = 0; i < img.data.size(); ++i) img.data[i] = float(i % 97) / 97.0f;
    const fs::path job = folder / "jobs" / *slowed_job;
    fs::create_directories(job);
    metrics::io::write_png((job / "shaded.png").string(), img);
    metrics::io::write_png((job / "error.png").string(), img);
    db.add_run(folder.string(), "commit" + std::to_string(run));
  }
  return history::write_history_report(db, (dir / "site").string());
}

TEST_F(history_chromium, IndexAndSeriesPageLoadEveryImageWithoutConsoleMessages) {
  const fs::path dir = test_folder("sb_history_chromium_");
  std::string slowed;
  const history::HistoryReport report = make_site(dir, &slowed);
  ASSERT_EQ(report.steps.size(), 1u);

  const BrowserRun index = run_chromium(chromium_, dir, dir / "site" / "index.html", "--dump-dom");
  ASSERT_EQ(index.exit_code, 0) << index.log;
  EXPECT_TRUE(index.console.empty()) << joined(index.console);
  EXPECT_NE(index.dom.find("data-images-ok=\"true\""), std::string::npos);
  // The script ran (sortable headers), the step's row names its commit.
  EXPECT_NE(index.dom.find("tabindex=\"0\""), std::string::npos);
  EXPECT_NE(index.dom.find("<td class=\"mono\">commit4</td>"), std::string::npos);
  EXPECT_NE(index.dom.find("<svg class=\"spark\""), std::string::npos);

  // The series page: its chart (SVG) and the four thumbnails load.
  const fs::path page = dir / "site" / report.steps[0].page;
  const BrowserRun series = run_chromium(chromium_, dir, page, "--dump-dom");
  ASSERT_EQ(series.exit_code, 0) << series.log;
  EXPECT_TRUE(series.console.empty()) << joined(series.console);
  EXPECT_NE(series.dom.find("data-images-ok=\"true\""), std::string::npos)
      << series.dom.substr(series.dom.find("<body"), 400);
  std::set<std::string> images;
  for (std::size_t at = series.dom.find("<img src=\""); at != std::string::npos;
       at = series.dom.find("<img src=\"", at + 1))
    images.insert(series.dom.substr(at + 10, series.dom.find('"', at + 10) - at - 10));
  EXPECT_EQ(images.size(), 5u);  // the chart, and shaded and error on both sides
  EXPECT_TRUE(images.count("../../run3/jobs/" + slowed + "/shaded.png"));
  EXPECT_TRUE(images.count("../../run4/jobs/" + slowed + "/error.png"));
}

TEST_F(history_chromium, AMissingImageOnASeriesPageIsReported) {
  const fs::path dir = test_folder("sb_history_chromium_");
  std::string slowed;
  const history::HistoryReport report = make_site(dir, &slowed);
  ASSERT_EQ(report.steps.size(), 1u);
  fs::remove(dir / "run4" / "jobs" / slowed / "shaded.png");  // after the site was written
  const BrowserRun series =
      run_chromium(chromium_, dir, dir / "site" / report.steps[0].page, "--dump-dom");
  ASSERT_EQ(series.exit_code, 0) << series.log;
  EXPECT_NE(series.dom.find("data-images-ok=\"false\""), std::string::npos);
  ASSERT_EQ(series.console.size(), 1u) << joined(series.console);
  EXPECT_NE(series.console[0].find("run4/jobs/" + slowed + "/shaded.png"), std::string::npos);
}

}  // namespace
}  // namespace sb::test
