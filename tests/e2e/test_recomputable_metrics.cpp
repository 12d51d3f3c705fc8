// Every visibility error a record holds can be recomputed from the files its
// run wrote: tools/recompute_metrics.py (OpenImageIO's Python bindings and
// numpy, the recipe docs/results.md gives) over configs/quick.json's jobs at
// a lower resolution, with the distance thirds on so that every region is
// there. A /usr/bin/python3 without OpenImageIO is a failure, not a skip:
// scripts/install-deps.sh --test installs python3-openimageio.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "e2e_util.h"

namespace sb::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

struct ScriptRun {
  int exit_code = -1;
  std::string output;
};

ScriptRun recompute(const std::string& run_dir) {
  const std::string cmd = "/usr/bin/python3 '" + std::string(SHADOWBENCH_SOURCE_DIR) +
                          "/tools/recompute_metrics.py' '" + run_dir + "' 2>&1";
  ScriptRun run;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (p == nullptr) return run;
  char buf[512];
  while (std::fgets(buf, sizeof buf, p) != nullptr) run.output += buf;
  const int status = ::pclose(p);
  if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
  return run;
}

json quick_at_low_resolution() {
  std::ifstream in(std::string(SHADOWBENCH_SOURCE_DIR) + "/configs/quick.json");
  json config = json::parse(in);
  config["resolutions"] = json::array({json::array({64, 48}), json::array({96, 72})});
  config["frames"] = {{"warmup", 0}, {"timed", 1}};
  config["reference"]["spp"] = 16;
  config["metrics"] = {{"distance_thirds", true}};
  return config;
}

TEST(RecomputableMetrics, OiioAndNumpyReproduceEveryRecordFromTheFiles) {
  const RunOutput out = run_config(quick_at_low_resolution(), "recomputable_metrics");
  ASSERT_EQ(out.records.size(), 20u);
  for (const json& r : out.records) {
    ASSERT_EQ(r["status"], "ok") << r["job_id"] << ": " << r.value("reason", "");
    // A mask for every region the record measured, each file present.
    const json& masks = r["images"].value("masks", json::object());
    for (const auto& [region, stats] : r["metrics"]["visibility"].items()) {
      ASSERT_TRUE(masks.contains(region)) << r["job_id"] << ": no mask for " << region;
      EXPECT_TRUE(fs::exists(fs::path(out.dir) / masks[region].get<std::string>()));
    }
  }
  const ScriptRun run = recompute(out.dir);
  ASSERT_NE(run.exit_code, 2) << "python3-openimageio missing or a file unreadable: " << run.output;
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("20 jobs"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find(" 0 mismatches"), std::string::npos) << run.output;
}

}  // namespace
}  // namespace sb::test
