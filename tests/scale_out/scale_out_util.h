#pragma once
// The driver run as a user runs it, into folders named for the running test.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../common/cli_run.h"

namespace sb::test {

inline CliRun run_shadowbench(const std::string& args) {
  return run_command("'" SHADOWBENCH_EXE "' " + args);
}

inline std::filesystem::path test_folder() { return test_folder("sb_scale_out_"); }

// configs/quick.json's 20 jobs (one scene, two resolutions, ten technique
// variants) at an eighth of its resolutions, with two timed frames and a
// 16-spp reference, written once per process; its path. Which jobs a shard
// runs, what each record holds and how shards merge do not depend on the
// sizes, and a run of quick.json itself took about 20 s, three of them
// and three shards most of this executable's 104 s.
inline std::string small_quick() {
  static const std::string path = [] {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("sb_scale_out_quick-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::ifstream in(SHADOWBENCH_SOURCE_DIR "/configs/quick.json");
    nlohmann::json config = nlohmann::json::parse(in);
    config["resolutions"] = {{40, 30}, {80, 60}};
    config["frames"] = {{"warmup", 1}, {"timed", 2}};
    config["reference"]["spp"] = 16;
    const auto file = dir / "quick.json";
    std::ofstream(file) << config.dump(2);
    return file.string();
  }();
  return path;
}

}  // namespace sb::test
