// The end-to-end case: a history of ten real runs of configs/ci.json,
// the last five with pcss 50 % slower (SHADOWBENCH_INJECT_DELAY, 50 % of each
// of its frames), added at ten commits; `shadowbench history report` must
// flag that job's time at the sixth commit and nothing else.
//
// Ten runs take about 50 s, more than a ctest entry may; so ctest runs them
// in five entries of two runs each (MakesItsBlockOfRuns, the block given by
// SB_HISTORY_BLOCK, entries test_history_ci_runs/block1..5, one after the
// other and alone: RUN_SERIAL, so that no neighbour's load moves the
// timings; block b makes runs b and b + 5, so that what load remains does
// not line up with the history's order), then the check
// (TheReportFlagsTheInjectedStepAtItsCommitAndNoOther), which needs them (a ctest fixture: `ctest
// -R check` runs the blocks too).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "../common/cli_run.h"
#include "../common/text.h"

namespace sb::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kRuns = 10, kRunsPerBlock = 2, kFirstSlowRun = 6;
constexpr const char* kSlowed = "pcss/size=1024";
const fs::path kFolder = "history_ci_runs";  // in the test's working folder (the build tree)
const std::string kExe = SHADOWBENCH_BINARY_DIR "/shadowbench";

fs::path run_dir(int run) { return kFolder / ("run" + std::to_string(run)); }

// A commit id of 40 hex digits, different per run.
std::string commit_of(int run) {
  char buf[41];
  std::snprintf(buf, sizeof buf, "%08x%032x", 0xc0ffee00u + unsigned(run), unsigned(run));
  return buf;
}

TEST(HistoryOfCiRuns, MakesItsBlockOfRuns) {
  const char* block_env = std::getenv("SB_HISTORY_BLOCK");
  if (block_env == nullptr)
    GTEST_SKIP() << "run by ctest's entries test_history_ci_runs/block<N>, which set "
                    "SB_HISTORY_BLOCK";
  const int block = std::atoi(block_env);
  ASSERT_GE(block, 1);
  ASSERT_LE(block, kRuns / kRunsPerBlock);
  if (block == 1) fs::remove_all(kFolder);  // a fresh history every time the test runs
  fs::create_directories(kFolder);
  // Block b makes run b (as it is) and run b + 5 (slowed): a busy spell on
  // the machine then falls on runs far apart in the history, each an outlier
  // the detector clips, not on a stretch of neighbouring runs, which would
  // be a level of its own.
  for (const int run : {block, block + kRuns / kRunsPerBlock}) {
    fs::remove_all(run_dir(run));
    const std::string delay =
        run >= kFirstSlowRun ? "SHADOWBENCH_INJECT_DELAY='" + std::string(kSlowed) + "@50%' " : "";
    const CliRun r =
        run_command(delay + kExe +
                    " run " SHADOWBENCH_SOURCE_DIR "/configs/ci.json --quiet --no-images --out " +
                    run_dir(run).string() + " --cache-dir " + (kFolder / "cache").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
}

TEST(HistoryOfCiRuns, TheReportFlagsTheInjectedStepAtItsCommitAndNoOther) {
  // The runs are what they should be: five as they are, five with the delay.
  for (int run = 1; run <= kRuns; ++run) {
    const auto records = jsonl_records(run_dir(run));
    ASSERT_EQ(records.size(), 5u) << run_dir(run) << ": run the blocks first (ctest does)";
    for (const json& j : records) {
      const bool slowed = j["technique_variant"] == kSlowed && run >= kFirstSlowRun;
      EXPECT_EQ(has(j.dump(), "SHADOWBENCH_INJECT_DELAY"), slowed)
          << "run " << run << ", " << j["technique_variant"];
    }
  }
  const fs::path db = kFolder / "history.sqlite", site = kFolder / "site";
  fs::remove(db);
  for (int run = 1; run <= kRuns; ++run) {
    const CliRun add = run_command(kExe + " history add " + run_dir(run).string() + " --db " +
                                   db.string() + " --commit " + commit_of(run));
    ASSERT_EQ(add.exit_code, 0) << add.output;
  }
  const CliRun report =
      run_command(kExe + " history report --db " + db.string() + " --out " + site.string());
  ASSERT_EQ(report.exit_code, 0) << report.output;

  const json steps = json::parse(read_text(site / "steps.json"));
  EXPECT_EQ(steps["runs"], kRuns);
  EXPECT_EQ(steps["series"], 5);
  ASSERT_EQ(steps["steps"].size(), 1u) << report.output;
  const json& s = steps["steps"][0];
  EXPECT_TRUE(s["series"].get<std::string>().ends_with(std::string("/ ") + kSlowed)) << s;
  EXPECT_EQ(s["quantity"], "time.frame_ratio");
  EXPECT_EQ(s["commit"], commit_of(kFirstSlowRun));
  EXPECT_EQ(s["previous_commit"], commit_of(kFirstSlowRun - 1));
  EXPECT_EQ(s["run_order"], kFirstSlowRun);
  // 50 % of each frame: the medians on both sides differ by about that. (A
  // 30 % step, 5 runs a side, is found in half the histories made on a
  // loaded machine, docs/ci.md: this test checks the way from runs to the
  // report, whatever the load, not the detector's power.)
  EXPECT_GT(s["relative_change"].get<double>(), 0.3) << s;
  EXPECT_LT(s["relative_change"].get<double>(), 0.7) << s;
  EXPECT_TRUE(fs::is_regular_file(site / s["page"].get<std::string>()));
}

}  // namespace
}  // namespace sb::test
