// `shadowbench compare` as a CI job runs it: exit 0 without a regression,
// 4 with one, 2 on bad input, and 2 when some job's time could not be
// compared (runs from other hosts, or --normalize control without a control).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_runner.h"
#include "results/compare.h"
#include "synthetic_run.h"

namespace {

using sb::test::make_controlled_record;
using sb::test::make_record;
using sb::test::noisy_samples;
using sb::test::on_host;
using sb::test::run_cli;
using sb::test::write_run;

std::vector<sb::record::JobRecord> run_of(double shadow_map_ms, double rmse, uint32_t seed,
                                          const std::string& run_id) {
  return {
      make_record("grid__320x240__none", noisy_samples(10.0, 0.03, 15, seed), 0.31, 0.55, run_id),
      make_record("grid__320x240__shadow_map--size=1024",
                  noisy_samples(shadow_map_ms, 0.03, 15, seed + 1), rmse, 0.27, run_id)};
}

TEST(CompareCli, NoRegressionExitsZero) {
  const auto base = write_run("cli_base", run_of(20.0, 0.10, 1, "base"));
  const auto jitter = write_run("cli_jitter", run_of(20.2, 0.101, 11, "jitter"));
  const auto r = run_cli("compare " + base + " " + jitter);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("grid__320x240__shadow_map--size=1024"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("0 regression(s)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(base)"), std::string::npos) << r.output;
}

TEST(CompareCli, SlowdownExitsWithTheRegressionCode) {
  const auto base = write_run("cli_base", run_of(20.0, 0.10, 1, "base"));
  const auto slow = write_run("cli_slow", run_of(26.0, 0.10, 21, "slow"));
  const auto r = run_cli("compare " + base + " " + slow);
  EXPECT_EQ(r.exit_code, sb::results::kExitRegression) << r.output;
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_NE(r.output.find("REGRESSION"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 job(s) regressed"), std::string::npos) << r.output;
  // A looser threshold lets it pass.
  EXPECT_EQ(run_cli("compare " + base + " " + slow + " --time-threshold 0.5").exit_code, 0);
  // So does a tiny alpha? No: 15 vs 15 separated samples give p = 3.4e-6.
  EXPECT_EQ(run_cli("compare " + base + " " + slow + " --alpha 1e-7").exit_code, 0);
}

TEST(CompareCli, ErrorRegressionExitsWithTheRegressionCode) {
  const auto base = write_run("cli_base", run_of(20.0, 0.10, 1, "base"));
  const auto worse = write_run("cli_worse", run_of(20.0, 0.11, 1, "worse"));
  auto r = run_cli("compare " + base + " " + worse);
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_NE(r.output.find("rmse 0.10000 -> 0.11000"), std::string::npos) << r.output;
  EXPECT_EQ(run_cli("compare " + base + " " + worse + " --error-threshold 0.02").exit_code, 0);
  r = run_cli("compare " + base + " " + worse + " --metric visibility.penumbra.rmse");
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

TEST(CompareCli, BadInputExitsWithTwo) {
  const auto base = write_run("cli_base", run_of(20.0, 0.10, 1, "base"));
  const auto empty = write_run("cli_empty", {});
  const auto other = write_run("cli_other", {make_record("elsewhere", {1, 2, 3}, 0.1, 0.2)});
  auto newer_records = run_of(20.0, 0.10, 1, "newer");
  newer_records[1].schema_version = 2;  // a record of a schema this build does not read
  const auto newer = write_run("cli_newer", newer_records);
  const std::string missing = base + "-missing";
  struct {
    std::string args, message;
  } cases[] = {
      {"compare " + base, "expected BASE_DIR NEW_DIR"},
      {"compare " + base + " " + missing, "no such run directory"},
      {"compare " + missing + " " + base, "no such run directory"},
      {"compare " + base + " " + empty, "no records"},
      {"compare " + base + " " + other, "no job in common"},
      {"compare " + base + " " + base + " --alpha 2", "--alpha"},
      {"compare " + base + " " + base + " --alpha x", "expected a number"},
      {"compare " + base + " " + base + " --time-threshold -1", "--time-threshold"},
      {"compare " + base + " " + base + " --metric visibility.all.nope", "no record has metrics"},
      {"compare " + base + " " + base + " --timing shading", "--timing"},
      {"compare " + base + " " + base + " --normalize ratio", "--normalize"},
      {"report " + base + " --normalize control",
       "goes with compare or compare-builds, not with report"},
      {"compare " + base + " " + newer,
       newer + "/results.jsonl: at line 2 (/schema_version): the record has schema_version 2; "
               "this shadowbench reads schema_version 1"},
      {"report " + newer, newer + "/results.jsonl: at line 2 (/schema_version)"},
      {"report " + base + " --alpha 0.1", "goes with compare or compare-builds, not with report"},
      {"validate x.json --benchmark-out b.json", "goes with run or report, not with validate"},
  };
  for (const auto& c : cases) {
    const auto r = run_cli(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << "\n" << r.output;
  }
  std::filesystem::create_directories(missing + "-norecords");
  EXPECT_EQ(run_cli("compare " + base + " " + missing + "-norecords").exit_code, 2);
}

TEST(CompareCli, OtherHostsAreNotComparedOnTime) {
  const auto amd = write_run("cli_amd", on_host(run_of(20.0, 0.10, 1, "amd"), "AMD EPYC 7B13"));
  const auto intel =
      write_run("cli_intel", on_host(run_of(40.0, 0.10, 2, "intel"), "Intel Xeon Platinum 8481C"));
  auto r = run_cli("compare " + amd + " " + intel);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  for (const char* part : {"cpu.model: \"AMD EPYC 7B13\" vs \"Intel Xeon Platinum 8481C\"",
                           "error metrics are compared whatever the host", "--normalize control",
                           "the time of 2 job(s) was not compared"})
    EXPECT_NE(r.output.find(part), std::string::npos) << part << "\n" << r.output;
  // Errors only, on purpose: green, or 4 on an error regression.
  r = run_cli("compare " + amd + " " + intel + " --timing none");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("time: not compared (--timing none)"), std::string::npos) << r.output;
  const auto worse = write_run(
      "cli_intel_worse", on_host(run_of(40.0, 0.12, 2, "worse"), "Intel Xeon Platinum 8481C"));
  EXPECT_EQ(run_cli("compare " + amd + " " + worse + " --timing none").exit_code, 4);
  EXPECT_EQ(run_cli("compare " + amd + " " + worse).exit_code, 4);  // 4 wins over 2
}

TEST(CompareCli, NormalizeControlComparesAcrossHosts) {
  auto controlled = [](double control_ms, double ratio, uint32_t seed, const std::string& cpu) {
    return on_host(
        {make_controlled_record("grid__320x240__pcf", noisy_samples(control_ms, 0.03, 15, seed),
                                noisy_samples(ratio, 0.03, 15, seed + 50), 0.05)},
        cpu);
  };
  const auto base = write_run("cli_ctl_base", controlled(10.0, 2.0, 1, "AMD EPYC 7B13"));
  const auto twice = write_run("cli_ctl_twice", controlled(20.0, 2.0, 2, "Intel Xeon"));
  const auto slower = write_run("cli_ctl_slower", controlled(20.0, 2.6, 3, "Intel Xeon"));
  auto r = run_cli("compare " + base + " " + twice + " --normalize control");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("--normalize control"), std::string::npos) << r.output;
  EXPECT_EQ(run_cli("compare " + base + " " + twice).exit_code, 2);
  r = run_cli("compare " + base + " " + slower + " --normalize control");
  EXPECT_EQ(r.exit_code, 4) << r.output;
  // No control in BASE: its time is not compared.
  const auto plain =
      write_run("cli_ctl_plain",
                {make_record("grid__320x240__pcf", noisy_samples(20, 0.03, 15, 4), 0.05, 0.1)});
  r = run_cli("compare " + plain + " " + twice + " --normalize control");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no timing.control in BASE"), std::string::npos) << r.output;
}

TEST(CompareCli, ListsJobsOnlyOnOneSide) {
  auto base_records = run_of(20.0, 0.10, 1, "base");
  base_records.push_back(make_record("gone", noisy_samples(5, 0.03, 15, 3), 0.1, 0.2));
  auto new_records = run_of(20.0, 0.10, 31, "new");
  new_records.push_back(make_record("added", noisy_samples(5, 0.03, 15, 4), 0.1, 0.2));
  const auto r = run_cli("compare " + write_run("cli_base2", base_records) + " " +
                         write_run("cli_new2", new_records));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("only in BASE (1):\n  gone"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("only in NEW (1):\n  added"), std::string::npos) << r.output;
}

// report writes the same files from an existing run directory.
TEST(CompareCli, ReportWritesTheCiOutputs) {
  const auto dir = write_run("cli_report", run_of(20.0, 0.10, 1, "report"));
  const std::string bench = dir + "/benchmark.json", bmf = dir + "/bencher.json";
  const auto r = run_cli("report " + dir + " --benchmark-out " + bench + " --bencher-out " + bmf);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream b(bench), m(bmf);
  const auto gb = nlohmann::json::parse(b);
  const auto bencher = nlohmann::json::parse(m);
  EXPECT_EQ(gb["benchmarks"].size(), 2u * 3u * 19u);  // 2 jobs × (frame + 2 passes) × (15 + 4)
  EXPECT_EQ(gb["context"]["shadowbench_run_id"], "report");
  EXPECT_TRUE(bencher.contains("grid__320x240__shadow_map--size=1024"));
}

// report also makes the charts and the HTML page, into RUN_DIR/report or --out.
TEST(CompareCli, ReportWritesChartsAndTheHtmlPage) {
  const auto dir = write_run("cli_report_html", run_of(20.0, 0.10, 1, "report"));
  const auto r = run_cli("report " + dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  namespace fs = std::filesystem;
  EXPECT_TRUE(fs::exists(fs::path(dir) / "report" / "index.html"));
  EXPECT_TRUE(fs::exists(fs::path(dir) / "report" / "heatmap_legend.png"));
  EXPECT_NE(r.output.find("chart: "), std::string::npos) << r.output;
  size_t charts = 0;
  for (const auto& e : fs::directory_iterator(fs::path(dir) / "report"))
    charts += e.path().extension() == ".svg";
  EXPECT_GE(charts, 2u);  // error against time and time per pass, at least

  const std::string out = dir + "_elsewhere";
  fs::remove_all(out);
  EXPECT_EQ(
      run_cli("report " + dir + " --out " + out + " --metric visibility.penumbra.rmse").exit_code,
      0);
  EXPECT_TRUE(fs::exists(fs::path(out) / "index.html"));
  const auto bad = run_cli("report " + dir + " --metric visibility.all.nonsense");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("visibility.all.nonsense"), std::string::npos) << bad.output;
}

}  // namespace
