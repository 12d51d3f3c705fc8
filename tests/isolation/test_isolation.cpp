// Jobs in child processes (run --isolation group|job): a crash, an abort, an
// exit or a hang fails that job alone, with how its process ended and its
// last stderr lines, and every other job's record is what it would have been.
#include <gtest/gtest.h>

#include <string>

#include "isolation_util.h"

namespace sb::test {
namespace {

using nlohmann::json;

bool has_line_containing(const json& record, const std::string& text) {
  if (!record.contains("child_stderr")) return false;
  for (const auto& line : record["child_stderr"])
    if (line.get<std::string>().find(text) != std::string::npos) return true;
  return false;
}

std::string reason(const json& record) { return record.value("reason", std::string()); }

const json kHealthy = json::array({"none", "shadow_map", "pcf_box"});

// The healthy jobs of a run in one process, without the faulty ones: what
// isolation must not change.
std::vector<json> healthy_alone(const std::filesystem::path& dir) {
  const auto config = write_config(dir, small_experiment(kHealthy));
  const auto out = (dir / "alone").string();
  const CliRun r = run_shadowbench("run " + config + " --out " + out +
                                   " --isolation none --no-cache --no-images --quiet");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return jsonl_records(out);
}

void expect_same_measurements(const json& isolated, const json& alone) {
  EXPECT_EQ(isolated["status"], "ok") << isolated.dump(1);
  EXPECT_EQ(isolated["spec_hash"], alone["spec_hash"]);
  EXPECT_EQ(isolated["reference"]["cache_key"], alone["reference"]["cache_key"]);
  // llvmpipe renders the same pixels in any process: the errors are equal.
  for (const char* region : {"all", "penumbra"})
    EXPECT_EQ(isolated["metrics"]["visibility"][region], alone["metrics"]["visibility"][region])
        << isolated["technique_variant"] << " " << region;
  EXPECT_EQ(isolated["classes"], alone["classes"]);
  EXPECT_FALSE(isolated.contains("child_stderr"));
}

void crashes_fail_only_their_own_jobs(const std::string& isolation) {
  const auto dir = test_folder();
  json techniques = json::array({"none",
                                 {{"name", "fault"}, {"params", {{"mode", "crash"}}}},
                                 "shadow_map",
                                 {{"name", "fault"}, {"params", {{"mode", "abort"}}}},
                                 {{"name", "fault"}, {"params", {{"mode", "exit"}}}},
                                 "pcf_box",
                                 {{"name", "fault"}, {"params", {{"mode", "throw"}}}}});
  const auto config = write_config(dir, small_experiment(techniques));
  const auto out = (dir / "run").string();
  const CliRun r = run_shadowbench("run " + config + " --out " + out + " --isolation " + isolation +
                                   " --no-cache --no-images");
  EXPECT_EQ(r.exit_code, 1) << r.output;  // jobs failed; the run finished
  EXPECT_NE(r.output.find("3 ok, 0 skipped, 4 failed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("of the failed, 3 crashed and 0 timed out"), std::string::npos)
      << r.output;
  const auto records = jsonl_records(out);
  ASSERT_EQ(records.size(), 7u);

  const json* crash = find_record(records, "fault/mode=crash");
  ASSERT_NE(crash, nullptr);
  EXPECT_EQ((*crash)["status"], "failed");
  EXPECT_NE(reason(*crash).find("killed by signal 11 (SIGSEGV"), std::string::npos)
      << reason(*crash);
  EXPECT_TRUE(has_line_containing(*crash, "fault plugin: about to crash")) << crash->dump(1);
  // Its record keeps what the job had before it died: the reference.
  EXPECT_TRUE(crash->contains("reference"));
  EXPECT_TRUE(crash->contains("duration_s"));

  const json* abort = find_record(records, "fault/mode=abort");
  ASSERT_NE(abort, nullptr);
  EXPECT_NE(reason(*abort).find("SIGABRT"), std::string::npos) << reason(*abort);
  EXPECT_TRUE(has_line_containing(*abort, "fault plugin: about to abort"));

  const json* exited = find_record(records, "fault/mode=exit");
  ASSERT_NE(exited, nullptr);
  EXPECT_NE(reason(*exited).find("exited with code 3"), std::string::npos) << reason(*exited);

  // A thrown error never needed a process of its own: failed in-process.
  const json* thrown = find_record(records, "fault/mode=throw");
  ASSERT_NE(thrown, nullptr);
  EXPECT_EQ((*thrown)["status"], "failed");
  EXPECT_NE(reason(*thrown).find("thrown on demand"), std::string::npos) << reason(*thrown);
  EXPECT_FALSE(thrown->contains("child_stderr"));

  const auto alone = healthy_alone(dir);
  ASSERT_EQ(alone.size(), 3u);
  for (const auto& healthy : alone) {
    const json* isolated = find_record(records, healthy["technique_variant"]);
    ASSERT_NE(isolated, nullptr) << healthy["technique_variant"];
    expect_same_measurements(*isolated, healthy);
  }
  // The report is written, with every job in it.
  EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / "summary.md"));
}

TEST(Isolation, CrashesAbortsAndExitsFailOnlyTheirOwnJobsInGroupIsolation) {
  crashes_fail_only_their_own_jobs("group");
}

TEST(Isolation, CrashesAbortsAndExitsFailOnlyTheirOwnJobsInJobIsolation) {
  crashes_fail_only_their_own_jobs("job");
}

TEST(Isolation, AHungJobIsKilledAtItsTimeLimitAndTheRunGoesOn) {
  const auto dir = test_folder();
  const auto config = write_config(
      dir, small_experiment(json::array(
               {{{"name", "fault"}, {"params", {{"mode", "hang"}, {"at", "prepare"}}}}, "none"})));
  const auto out = (dir / "run").string();
  const CliRun r =
      run_shadowbench("run " + config + " --out " + out + " --job-timeout 2 --no-cache --quiet");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("of the failed, 0 crashed and 1 timed out"), std::string::npos)
      << r.output;
  const auto records = jsonl_records(out);
  ASSERT_EQ(records.size(), 2u);
  const json* hung = find_record(records, "fault/mode=hang,at=prepare");
  ASSERT_NE(hung, nullptr) << records[0].dump(1);
  EXPECT_EQ((*hung)["status"], "failed");
  EXPECT_NE(reason(*hung).find("timed out after 2 s (limits.job_seconds"), std::string::npos)
      << reason(*hung);
  EXPECT_TRUE(has_line_containing(*hung, "fault plugin: about to hang"));
  EXPECT_GE((*hung)["duration_s"].get<double>(), 2.0);
  const json* after = find_record(records, "none");
  ASSERT_NE(after, nullptr);
  EXPECT_EQ((*after)["status"], "ok");
}

TEST(Isolation, TheConfigsJobLimitAppliesWithoutTheOption) {
  const auto dir = test_folder();
  json config = small_experiment(
      json::array({{{"name", "fault"}, {"params", {{"mode", "hang"}, {"at", "prepare"}}}}}));
  config["limits"] = {{"job_seconds", 1}};
  const auto out = (dir / "run").string();
  const CliRun r =
      run_shadowbench("run " + write_config(dir, config) + " --out " + out + " --no-cache --quiet");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto records = jsonl_records(out);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_NE(reason(records[0]).find("timed out after 1 s"), std::string::npos)
      << reason(records[0]);
}

TEST(Isolation, ASetUpThatOverrunsFailsEveryJobOfItsGroupWithTheReason) {
  const auto dir = test_folder();
  json config = small_experiment(json::array({"none", "shadow_map"}));
  // Thousands of samples per pixel at 640×480: longer than the 1 s allowed.
  config["resolutions"] = {"640x480"};
  config["reference"] = {{"spp", 4096}};
  config["limits"] = {{"setup_seconds", 1}};
  const auto out = (dir / "run").string();
  const CliRun r =
      run_shadowbench("run " + write_config(dir, config) + " --out " + out + " --no-cache --quiet");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto records = jsonl_records(out);
  ASSERT_EQ(records.size(), 2u);
  for (const auto& rec : records) {
    EXPECT_EQ(rec["status"], "failed");
    EXPECT_EQ(reason(rec).rfind("the set-up of sphere_grid", 0), 0u) << reason(rec);
    EXPECT_NE(reason(rec).find("@ 640x480 (scene, G-buffer, reference) timed out after 1 s "
                               "(limits.setup_seconds)"),
              std::string::npos)
        << reason(rec);
    // The child made its context before it was killed: the record names it.
    EXPECT_NE(rec["gl_renderer"].get<std::string>().find("llvmpipe"), std::string::npos);
  }
}

TEST(Isolation, WithoutIsolationAJobTimeoutIsNotEnforcedAndSaysSo) {
  const auto dir = test_folder();
  const auto config = write_config(dir, small_experiment(json::array({"none"})));
  const CliRun r = run_shadowbench("run " + config + " --out " + (dir / "run").string() +
                                   " --isolation none --job-timeout 5 --no-cache --quiet");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("--job-timeout is enforced only with --isolation group or job"),
            std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace sb::test
