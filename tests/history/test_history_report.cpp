// The history's static site (history/history_report.h), on histories whose
// steps are known by construction: copies of the ci baseline's records with
// seeded noise and one change put in on purpose. What is checked is what a
// reader of the site and of steps.json gets: which step, at which commit,
// with links to the runs on both sides, and nothing else flagged.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "../common/cli_run.h"
#include "../common/text.h"
#include "core/error.h"
#include "core/image.h"
#include "history/history_db.h"
#include "history/history_report.h"
#include "history_fixture.h"
#include "metrics/image_io.h"
#include "record/figures.h"

namespace sb::test {
namespace {

namespace fs = std::filesystem;
using history::HistoryDb;
using history::HistoryReport;
using history::HistoryReportOptions;
using nlohmann::json;

const json::json_pointer kRatio("/timing/control/frame_ratio/median");
const json::json_pointer kFrameMs("/timing/frame/median_ms");
const json::json_pointer kRmse("/metrics/visibility/geometry/rmse");

// How a history's runs differ from the baseline.
struct Change {
  std::string job;          // the job changed ("" none)
  int from_run = 0;         // the first run (0-based) it is changed in
  double time_factor = 1;   // on its time ratio and frame time
  double error_factor = 1;  // on its geometry RMSE
};

// `runs` run folders in dir (run0, run1, ...) added at commits c0, c1, ...
// to the history dir/h.sqlite, whose path it returns; every job's time ratio
// and frame time with 2 % lognormal noise (seeded), host fingerprints from
// `host_of(run)` when given.
std::string make_history(const fs::path& dir, int runs, const Change& change,
                         const std::function<std::string(int)>& host_of = {}) {
  HistoryDb db((dir / "h.sqlite").string());
  std::mt19937_64 rng(7);
  std::normal_distribution<double> z(0.0, 1.0);
  for (int run = 0; run < runs; ++run) {
    const fs::path folder = run_folder(dir, "run" + std::to_string(run), [&](json& j) {
      start_on_day(j, run + 1);
      if (host_of) j["host"]["fingerprint"] = host_of(run);
      const bool changed = j["job_id"] == change.job && run >= change.from_run;
      const double noise = std::exp(0.02 * z(rng));
      for (const auto& p : {kRatio, kFrameMs})
        if (j.contains(p)) j[p] = j[p].get<double>() * noise * (changed ? change.time_factor : 1);
      if (changed && j.contains(kRmse)) j[kRmse] = j[kRmse].get<double>() * change.error_factor;
    });
    db.add_run(folder.string(), "c" + std::to_string(run));
  }
  return db.path();
}

std::string baseline_job(std::size_t i) { return jsonl_records(kCiBaseline).at(i)["job_id"]; }
std::string baseline_technique(std::size_t i) {
  return jsonl_records(kCiBaseline).at(i)["technique_variant"];
}

json steps_of(const fs::path& site) { return json::parse(read_text(site / "steps.json")); }

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(HistoryReport, TenRunsWithOneJobThirtyPercentSlowerFromTheSixthFlagThatCommitAndNoOther) {
  const fs::path dir = test_folder("sb_history_report_");
  const HistoryDb db(make_history(dir, 10, {baseline_job(2), 5, 1.3, 1}));
  const fs::path site = dir / "site";
  const HistoryReport report = history::write_history_report(db, site.string());

  EXPECT_EQ(report.runs, 10u);
  EXPECT_EQ(report.series, jsonl_records(kCiBaseline).size());
  ASSERT_EQ(report.steps.size(), 1u);
  const json steps = steps_of(site);
  ASSERT_EQ(steps["steps"].size(), 1u) << steps.dump(1);
  const json& s = steps["steps"][0];
  EXPECT_EQ(s["quantity"], "time.frame_ratio");
  EXPECT_NE(s["series"].get<std::string>().find(baseline_technique(2)), std::string::npos);
  EXPECT_EQ(s["commit"], "c5");
  EXPECT_EQ(s["previous_commit"], "c4");
  EXPECT_EQ(s["run_order"], 6);
  EXPECT_NEAR(s["relative_change"].get<double>(), 0.3, 0.05);
  EXPECT_EQ(s["runs_before"], 5);
  EXPECT_EQ(s["runs_after"], 5);

  // The index lists it and links its series page, which exists with its chart.
  const std::string index = read_text(site / "index.html");
  const std::string page = s["page"];
  EXPECT_NE(index.find("href=\"" + page + "\""), std::string::npos) << page;
  EXPECT_EQ(count(index, "<td class=\"num steps\">"), 1u);  // one series with a step
  ASSERT_TRUE(fs::is_regular_file(site / page));
  const fs::path stem = (site / page).replace_extension("");
  ASSERT_TRUE(fs::is_regular_file(stem.string() + ".png"));
  const std::string svg = read_text(stem.string() + ".svg");
  EXPECT_NE(svg.find(baseline_technique(2)), std::string::npos);  // the title, as text
  EXPECT_NE(svg.find(">step<"), std::string::npos);               // the step's legend entry
}

TEST(HistoryReport, AStepLinksTheRunsOnBothSidesAndTheirImages) {
  const fs::path dir = test_folder("sb_history_report_");
  const std::string slowed = baseline_job(1);
  const HistoryDb db(make_history(dir, 9, {slowed, 4, 1.4, 1}));
  // The last run before the step has its images; the first after has none.
  core::ImageF img(4, 3, 3);
  fs::create_directories(dir / "run3" / "jobs" / slowed);
  metrics::io::write_png((dir / "run3" / "jobs" / slowed / "shaded.png").string(), img);
  metrics::io::write_png((dir / "run3" / "jobs" / slowed / "error.png").string(), img);
  fs::create_directories(dir / "run4" / "report");
  write_text(dir / "run4" / "report" / "index.html", "<html></html>");
  const fs::path site = dir / "site";
  const HistoryReport report = history::write_history_report(db, site.string());
  ASSERT_EQ(report.steps.size(), 1u);
  EXPECT_EQ(report.steps[0].commit, "c4");

  // From site/series/<page>: ../../runN is the run folder.
  const std::string page = read_text(site / report.steps[0].page);
  EXPECT_NE(page.find("<th>last run before</th><td class=\"num\">4</td>"), std::string::npos);
  EXPECT_NE(page.find("<th>first run after</th><td class=\"num\">5</td>"), std::string::npos);
  EXPECT_NE(page.find("href=\"../../run3\""), std::string::npos);
  EXPECT_NE(page.find("href=\"../../run4\""), std::string::npos);
  EXPECT_NE(page.find("href=\"../../run4/report/index.html\""), std::string::npos);
  EXPECT_EQ(page.find("href=\"../../run3/report/index.html\""), std::string::npos);
  const std::string images = "../../run3/jobs/" + slowed;
  EXPECT_NE(page.find("<img src=\"" + images + "/shaded.png\""), std::string::npos) << images;
  EXPECT_NE(page.find("<img src=\"" + images + "/error.png\""), std::string::npos);
  EXPECT_EQ(count(page, "<img src=\"../../run"), 2u);  // none for the run without images

  // A run folder that is gone is said to be, not linked.
  fs::remove_all(dir / "run3");
  history::write_history_report(db, site.string());
  const std::string again = read_text(site / report.steps[0].page);
  EXPECT_EQ(again.find("href=\"../../run3\""), std::string::npos);
  EXPECT_NE(again.find("not on this machine"), std::string::npos);
  EXPECT_EQ(count(again, "<img src=\"../../run"), 0u);
}

TEST(HistoryReport, AnErrorStepIsFoundOnItsOwnScaleAndTheTimesStayFlat) {
  const fs::path dir = test_folder("sb_history_report_");
  // 8 % more error from the sixth run on; the times are as noisy as ever.
  const HistoryDb db(make_history(dir, 10, {baseline_job(3), 5, 1, 1.08}));
  const HistoryReport report = history::write_history_report(db, (dir / "site").string());
  ASSERT_EQ(report.steps.size(), 1u);
  EXPECT_EQ(report.steps[0].quantity, "metrics.visibility.geometry.rmse");
  EXPECT_EQ(report.steps[0].commit, "c5");
  EXPECT_NEAR(report.steps[0].change.relative_change, 0.08, 1e-9);  // errors are not noisy
  // Another metric than the one that moved: no step.
  HistoryReportOptions other;
  other.quantities.error = "metrics.visibility.penumbra.rmse";
  EXPECT_TRUE(history::write_history_report(db, (dir / "site2").string(), other).steps.empty());
}

TEST(HistoryReport, MillisecondsAcrossHostsCarryABannerAndRatiosDoNot) {
  const fs::path dir = test_folder("sb_history_report_");
  const HistoryDb db(make_history(dir, 8, {}, [](int run) {
    return run < 4 ? std::string("aaaaaaaaaaaaaaaa") : std::string("bbbbbbbbbbbbbbbb");
  }));
  HistoryReportOptions ms;
  ms.quantities.time = "time.frame_ms";
  const HistoryReport in_ms = history::write_history_report(db, (dir / "ms").string(), ms);
  EXPECT_EQ(in_ms.hosts, 2u);
  const std::string banner = "not comparable";
  EXPECT_NE(read_text(dir / "ms" / "index.html").find(banner), std::string::npos);
  const HistoryReport ratio = history::write_history_report(db, (dir / "ratio").string());
  const std::string index = read_text(dir / "ratio" / "index.html");
  EXPECT_EQ(index.find(banner), std::string::npos);
  EXPECT_NE(index.find("host 1 (aaaaaaaaaaaa)"), std::string::npos);
  EXPECT_NE(index.find("host 2 (bbbbbbbbbbbb)"), std::string::npos);
  // Every run's host on the series pages, and one marker set per host in the chart.
  const std::string page = read_text(dir / "ratio" / "series" / (baseline_job(0) + ".html"));
  EXPECT_EQ(count(page, "<td>host 1 (aaaaaaaaaaaa)</td>"), 4u);
  EXPECT_EQ(count(page, "<td>host 2 (bbbbbbbbbbbb)</td>"), 4u);
  const json chart = json::parse(read_text(dir / "ratio" / "series" / (baseline_job(0) + ".json")));
  EXPECT_EQ(chart["hosts"], json({0, 0, 0, 0, 1, 1, 1, 1}));
  EXPECT_EQ(ratio.steps.size(), 0u);
}

TEST(HistoryReport, ARunWithoutAJobBreaksItsSparklineAndItsRowSaysSo) {
  const fs::path dir = test_folder("sb_history_report_");
  const std::string gone = baseline_job(0);
  HistoryDb db((dir / "h.sqlite").string());
  for (int run = 0; run < 5; ++run) {
    const fs::path folder =
        run_folder(dir, "run" + std::to_string(run), [&](json& j) { start_on_day(j, run + 1); });
    if (run == 2) {  // the records without that job
      std::string kept;
      for (const json& j : jsonl_records(folder))
        if (j["job_id"] != gone) kept += j.dump() + "\n";
      write_text(folder / "results.jsonl", kept);
    }
    db.add_run(folder.string(), "c" + std::to_string(run));
  }
  const fs::path site = dir / "site";
  history::write_history_report(db, site.string());
  const std::string index = read_text(site / "index.html");
  const std::size_t row = index.find("<a href=\"series/" + gone + ".html\">");
  ASSERT_NE(row, std::string::npos);
  const std::string cells = index.substr(row, index.find("</tr>", row) - row);
  EXPECT_EQ(count(cells, "<polyline"), 4u);  // time and error, each in two pieces
  EXPECT_NE(cells.find("<td class=\"num\">4</td>"), std::string::npos);  // runs with the job
  const std::string page = read_text(site / "series" / (gone + ".html"));
  EXPECT_NE(page.find("not in this run"), std::string::npos);
}

TEST(HistoryReport, UnknownQuantitiesAreRefusedNamingTheOption) {
  const fs::path dir = test_folder("sb_history_report_");
  const HistoryDb db(make_history(dir, 2, {}));
  HistoryReportOptions bad_time;
  bad_time.quantities.time = "time.wall_ms";
  HistoryReportOptions bad_metric;
  bad_metric.quantities.error = "metrics.visibility.geometry.rms";
  // Each message lists what may be given, from the catalogue (record/figures.h).
  for (const auto& [options, option] : {std::pair{bad_time, "--time"}, {bad_metric, "--metric"}}) {
    try {
      history::write_history_report(db, (dir / "site").string(), options);
      ADD_FAILURE() << "no error for " << option;
    } catch (const core::InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(option), std::string::npos) << what;
      if (std::string(option) == "--metric")
        EXPECT_NE(what.find(record::metric_path_syntax()), std::string::npos) << what;
      else
        for (const auto& t : record::time_series())
          EXPECT_NE(what.find(t.key), std::string::npos) << what;
    }
  }
}

TEST(HistoryReport, TheCommandWritesTheSitePrintsTheStepsAndRefusesAMissingHistory) {
  const fs::path dir = test_folder("sb_history_report_");
  make_history(dir, 10, {baseline_job(4), 5, 1.3, 1});
  const std::string exe = SHADOWBENCH_BINARY_DIR "/shadowbench";
  const CliRun ok = run_command(exe + " history report --db " + (dir / "h.sqlite").string() +
                                " --out " + (dir / "site").string());
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("10 runs, 5 series, 1 host(s), 1 step(s)"), std::string::npos)
      << ok.output;
  EXPECT_NE(ok.output.find("step at run 6 (commit c5)"), std::string::npos) << ok.output;
  EXPECT_TRUE(fs::is_regular_file(dir / "site" / "index.html"));

  const CliRun missing =
      run_command(exe + " history report --db " + (dir / "none.sqlite").string() + " --out " +
                  (dir / "site2").string());
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find((dir / "none.sqlite").string()), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "none.sqlite"));  // not created by asking for its report
  const CliRun bad_time =
      run_command(exe + " history report --db " + (dir / "h.sqlite").string() + " --time seconds");
  EXPECT_EQ(bad_time.exit_code, 2) << bad_time.output;
}

}  // namespace
}  // namespace sb::test

namespace sb::test {
namespace {

// Ten runs; the last three of one job measured beside a busy machine: its
// time ratio 25 % up, and, when `spread`, its frames' ratios spread as a
// loaded machine spreads them (each times exp(0.5 z)), as its samples say.
std::string history_with_a_busy_spell(const fs::path& dir, bool spread) {
  HistoryDb db((dir / "h.sqlite").string());
  std::mt19937_64 rng(8);
  std::normal_distribution<double> z(0.0, 1.0);
  const json::json_pointer samples("/timing/control/frame_ratio/samples");
  for (int run = 0; run < 10; ++run) {
    const fs::path folder = run_folder(dir, "run" + std::to_string(run), [&](json& j) {
      start_on_day(j, run + 1);
      const double noise = std::exp(0.02 * z(rng));
      const bool busy = j["job_id"] == baseline_job(2) && run >= 7;
      if (j.contains(kRatio)) j[kRatio] = j[kRatio].get<double>() * noise * (busy ? 1.25 : 1);
      if (busy && spread)
        for (json& v : j[samples]) v = v.get<double>() * std::exp(0.5 * z(rng));
    });
    db.add_run(folder.string(), "c" + std::to_string(run));
  }
  return db.path();
}

TEST(HistoryReport, ThreeRunsThatSayTheyWereLoadedMakeNoStepAndAreMarkedLoaded) {
  const fs::path dir = test_folder("sb_history_report_");
  // Without their own noise saying so, the three runs are a level of their own.
  const HistoryDb quiet(history_with_a_busy_spell(dir / "quiet", false));
  const HistoryReport stepped = history::write_history_report(quiet, (dir / "quiet_site").string());
  ASSERT_EQ(stepped.steps.size(), 1u);
  EXPECT_EQ(steps_of(dir / "quiet_site")["steps"][0]["run_order"], 8);

  const HistoryDb busy(history_with_a_busy_spell(dir / "busy", true));
  const fs::path site = dir / "busy_site";
  EXPECT_TRUE(history::write_history_report(busy, site.string()).steps.empty());
  // The job's page shows each run's own noise and marks the three as loaded.
  for (const auto& entry : fs::directory_iterator(site / "series")) {
    if (entry.path().extension() != ".html") continue;
    const std::string page = read_text(entry.path());
    const bool the_job = page.find(baseline_technique(2)) != std::string::npos;
    EXPECT_EQ(count(page, "<em>loaded</em></td>"), the_job ? 3u : 0u) << entry.path();
    EXPECT_NE(page.find("its own noise"), std::string::npos);
  }
}

}  // namespace
}  // namespace sb::test
