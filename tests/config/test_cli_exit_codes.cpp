// The driver's exit codes: 2 for bad input, with the message on stderr.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_runner.h"

namespace {

using sb::test::run_cli;

// A folder of this process's own: the shards of this executable run side by side.
std::filesystem::path cli_dir() {
  return std::filesystem::temp_directory_path() /
         ("shadowbench_test_cli-" + std::to_string(::getpid()));
}

std::string write_temp(const std::string& name, const std::string& text) {
  const auto dir = cli_dir();
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

TEST(Cli, BadConfigExitsWithTwo) {
  const std::string config =
      R"({"scenes": [{"type": "sphere_grid"}], "techniques": [{"name": "pcf_box", "params": {"k": 4}}], "resolutions": [[8, 8]]})";
  const std::string path = write_temp("bad.json", config);
  for (const char* command : {"validate", "run"}) {
    // validate takes no --out; run must not create it for a bad config.
    const std::string out = std::string(command) == "run" ? " --out " + path + ".out" : "";
    std::string args(command);
    args.append(" ").append(path).append(out);
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    const std::string at = R"({"k": 4})";
    const std::string line_col = ":1:" + std::to_string(config.find(at) + at.find('4') + 1);
    EXPECT_NE(r.output.find(path + line_col +
                            " (/techniques/0/params/k): parameter 'k': expected an odd "
                            "integer, found 4"),
              std::string::npos)
        << r.output;
  }
  EXPECT_FALSE(std::filesystem::exists(path + ".out")) << "nothing may be written for a bad config";
}

// (Running such a config is tested in tests/e2e: it needs GL.)
TEST(Cli, BadSceneFileFailsValidation) {
  const auto dir = cli_dir();
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(SHADOWBENCH_SOURCE_DIR "/tests/gltf/corpus/index_out_of_range.gltf",
                             dir / "bad.gltf", std::filesystem::copy_options::overwrite_existing);
  const std::string path =
      write_temp("bad_scene.json",
                 R"({"scenes": [{"type": "gltf", "params": {"file": "bad.gltf"}},
                     {"type": "sphere_grid", "params": {"grid": 2}}],
          "techniques": ["none"], "resolutions": [[16, 12]],
          "frames": {"warmup": 0, "timed": 1}, "reference": {"spp": 4}})");
  const auto v = run_cli("validate " + path);
  EXPECT_EQ(v.exit_code, 2) << v.output;
  EXPECT_NE(v.output.find("bad.gltf: at accessor 1"), std::string::npos) << v.output;
}

TEST(Cli, UnknownOptionAndCommandExitWithTwo) {
  EXPECT_EQ(run_cli("run --frobnicate").exit_code, 2);
  EXPECT_EQ(run_cli("frobnicate").exit_code, 2);
  EXPECT_EQ(run_cli("run").exit_code, 2);
  EXPECT_EQ(run_cli("run x.json --backend vulkan").exit_code, 2);
}

TEST(Cli, ValidateAcceptsTheQuickConfig) {
  const auto r = run_cli("validate " SHADOWBENCH_SOURCE_DIR "/configs/quick.json");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("jobs"), std::string::npos) << r.output;
}

TEST(Cli, ListShowsTechniquesWithTheirNeeds) {
  const auto r = run_cli("list");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  for (const char* name :
       {"none", "shadow_map", "pcf_box", "shadow_volume", "accumulation", "sphere_grid"})
    EXPECT_NE(r.output.find(name), std::string::npos) << name;
  EXPECT_NE(r.output.find("needs: closed_casters edge_adjacency"), std::string::npos) << r.output;
}

}  // namespace
