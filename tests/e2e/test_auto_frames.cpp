// frames.timed "auto" through the driver: each job's frames grow a block at
// a time until its median's interval is within the target or a bound comes
// first, and its record and console line say how many and why.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../common/cli_run.h"
#include "../common/text.h"
#include "../config/cli_runner.h"
#include "e2e_util.h"

namespace sb::test {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

CliResult run_auto(const fs::path& dir, const json& frames) {
  const json config = {
      {"name", "auto"},
      {"scenes", {small_scene(2.0)}},
      {"techniques", {"shadow_map", {{"name", "pcf_box"}, {"params", {{"k", 3}}}}}},
      {"resolutions", {{64, 48}}},
      {"frames", frames},
      {"reference", {{"spp", 4}}}};
  std::ofstream(dir / "auto.json") << config.dump(2);
  return run_cli("run " + (dir / "auto.json").string() + " --out " + (dir / "run").string() +
                 " --no-images --cache-dir " + (dir / "cache").string());
}

TEST(AutoFrames, EachJobSaysHowManyFramesItTimedAndWhyItStopped) {
  const fs::path dir = fresh_test_folder("auto_frames_");
  const CliResult run = run_auto(dir, {{"warmup", 1},
                                       {"timed", "auto"},
                                       {"auto_block", 5},
                                       {"auto_target", 0.2},
                                       {"auto_max_frames", 30}});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto records = jsonl_records(dir / "run");
  ASSERT_EQ(records.size(), 2u);
  for (const json& r : records) {
    const json& t = r["timing"];
    ASSERT_TRUE(t.contains("auto")) << t.dump();
    const json& chosen = t["auto"];
    const int timed = t["timed_frames"];
    EXPECT_EQ(chosen["block"], 5);
    EXPECT_EQ(chosen["target"], 0.2);
    EXPECT_EQ(timed % 5, 0);
    EXPECT_LE(timed, 30);
    EXPECT_EQ(t["frame"]["samples_ms"].size(), static_cast<size_t>(timed));
    // Why it stopped is true of the frames it kept.
    const double judged = std::max(t["frame"]["median_ci_rel"].get<double>(),
                                   t["control"]["frame_ratio"]["median_ci_rel"].get<double>());
    EXPECT_DOUBLE_EQ(chosen["half_width"].get<double>(), judged);
    if (chosen["stop"] == "target") {
      EXPECT_LE(judged, 0.2);
    } else {
      EXPECT_EQ(chosen["stop"], "max_frames") << chosen.dump();
      EXPECT_EQ(timed, 30);
      EXPECT_GT(judged, 0.2);
    }
    // Its console line says the same.
    const std::string said =
        std::to_string(timed) + " frames (" +
        (chosen["stop"] == "target" ? std::string("interval within target")
                                    : chosen["stop"].get<std::string>() + " reached") +
        ")";
    const size_t line = run.output.find(r["technique_variant"].get<std::string>() + ": ok");
    ASSERT_NE(line, std::string::npos) << run.output;
    EXPECT_NE(run.output.substr(line, run.output.find('\n', line) - line).find(said),
              std::string::npos)
        << said << "\n"
        << run.output;
  }
}

TEST(AutoFrames, ATargetNoFramesReachStopsAtTheFrameBound) {
  const fs::path dir = fresh_test_folder("auto_frames_bound_");
  // 0.1 % of a llvmpipe frame's median from 10 frames: never.
  const CliResult run = run_auto(dir, {{"warmup", 1},
                                       {"timed", "auto"},
                                       {"auto_block", 5},
                                       {"auto_target", 0.001},
                                       {"auto_max_frames", 10}});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  for (const json& r : jsonl_records(dir / "run")) {
    EXPECT_EQ(r["timing"]["auto"]["stop"], "max_frames");
    EXPECT_EQ(r["timing"]["timed_frames"], 10);
  }
  EXPECT_NE(run.output.find("10 frames (max_frames reached)"), std::string::npos) << run.output;
}

}  // namespace

}  // namespace sb::test
