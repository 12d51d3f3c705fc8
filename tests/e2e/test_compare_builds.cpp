// `shadowbench compare-builds`: two builds run one config taking turns and
// are compared. The same binary stands in for both builds; a wrapper that
// sets SHADOWBENCH_INJECT_DELAY stands in for a slower one.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "../config/cli_runner.h"
#include "e2e_util.h"
#include "store/results_store.h"

namespace sb::test {

using record::JobStatus;
using store::read_job_records;

namespace {

namespace fs = std::filesystem;

std::string write_config(const fs::path& dir, int timed_frames = 6) {
  const nlohmann::json config = {
      {"name", "ab"},
      {"scenes", {small_scene(2.0)}},
      {"techniques", {"none", {{"name", "shadow_map"}, {"params", {{"size", 256}}}}}},
      {"resolutions", {{64, 48}}},
      {"frames", {{"warmup", 1}, {"timed", timed_frames}}},
      {"reference", {{"spp", 16}}}};
  const fs::path path = dir / "ab.json";
  std::ofstream(path) << config.dump(2);
  return path.string();
}

TEST(CompareBuilds, BothBuildsTakeTurnsAndTheirRunsAreComplete) {
  const fs::path dir = fresh_test_folder("compare_builds_");
  const std::string config = write_config(dir);
  // A threshold no noise reaches: this test is about the mechanics.
  const auto r =
      run_cli("compare-builds --base " SHADOWBENCH_EXE " --new " SHADOWBENCH_EXE " " + config +
              " --out " + (dir / "out").string() +
              " --turn-block 2 --time-threshold 10 --cache-dir " + (dir / "cache").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("host: same host fingerprint"), std::string::npos) << r.output;
  // 1 start + 3 blocks per job × 2 jobs.
  EXPECT_NE(r.output.find("base: " + (dir / "out" / "base").string() + ", 7 turns, exit code 0"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("new: " + (dir / "out" / "new").string() + ", 7 turns, exit code 0"),
            std::string::npos)
      << r.output;
  const auto base = read_job_records((dir / "out" / "base").string());
  const auto fresh = read_job_records((dir / "out" / "new").string());
  ASSERT_EQ(base.size(), 2u);
  ASSERT_EQ(fresh.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(base[i].job_id, fresh[i].job_id);
    EXPECT_EQ(base[i].status, JobStatus::Ok);
    ASSERT_TRUE(base[i].timing && fresh[i].timing);
    EXPECT_EQ(base[i].timing->frame.samples.size(), 6u);
    EXPECT_EQ(base[i].metrics->to_json(), fresh[i].metrics->to_json());
  }
}

TEST(CompareBuilds, AnInjectedSlowdownInTheNewBuildIsItsJobsRegressionOnly) {
  const fs::path dir = fresh_test_folder("compare_builds_slow_");
  // Twelve frames a job: with six, p could not go below 0.002, and a
  // couple of base frames slowed by whatever else ran on the machine put
  // it above alpha (in CI: p = 0.041 at a +3726 % change).
  const std::string config = write_config(dir, 12);
  // The "new build": the same binary, 60 ms slower per shadow_map frame.
  const fs::path slower = dir / "slower.sh";
  std::ofstream(slower) << "#!/bin/sh\nSHADOWBENCH_INJECT_DELAY='shadow_map/size=256@60' exec "
                        << SHADOWBENCH_EXE << " \"$@\"\n";
  fs::permissions(slower, fs::perms::owner_all);
  // Alpha per job (--correction none), since this test is about which job
  // is flagged, not about the correction across jobs
  // (tests/compare/test_family_wise.cpp).
  const auto r =
      run_cli("compare-builds --base " SHADOWBENCH_EXE " --new " + slower.string() + " " + config +
              " --out " + (dir / "out").string() +
              " --time-threshold 1.0 --correction none --cache-dir " + (dir / "cache").string());
  EXPECT_EQ(r.exit_code, 4) << r.output;
  // By default the builds are compared on the ratios to the control.
  EXPECT_NE(r.output.find("(--normalize control)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("__shadow_map--size=256: regression: frame/control ratio"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("__none: regression"), std::string::npos) << r.output;
}

TEST(CompareBuilds, AMissingBuildIsBadInputNamingIt) {
  const fs::path dir = fresh_test_folder("compare_builds_missing_");
  const std::string config = write_config(dir);
  const auto r =
      run_cli("compare-builds --base /nonexistent/shadowbench --new " SHADOWBENCH_EXE " " + config);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("/nonexistent/shadowbench"), std::string::npos) << r.output;
  const auto no_new = run_cli("compare-builds --base " SHADOWBENCH_EXE " " + config);
  EXPECT_EQ(no_new.exit_code, 2) << no_new.output;
  EXPECT_NE(no_new.output.find("--new"), std::string::npos) << no_new.output;
}

}  // namespace
}  // namespace sb::test
