#pragma once
// The driver run as a user runs it, with the test-only fault plugin on
// $SHADOWBENCH_PLUGIN_PATH, into folders of the running test's name.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sb::test {

struct CliRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

inline std::string shadowbench_command(const std::string& args) {
  return "SHADOWBENCH_PLUGIN_PATH='" FAULT_PLUGIN_DIR "' '" SHADOWBENCH_EXE "' " + args;
}

inline CliRun run_shadowbench(const std::string& args) {
  FILE* pipe = ::popen((shadowbench_command(args) + " 2>&1").c_str(), "r");
  CliRun r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), int(buf.size()), pipe) != nullptr) r.output += buf.data();
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// An empty folder named for the running test.
inline std::filesystem::path test_folder() {
  auto dir = std::filesystem::temp_directory_path() /
             ("sb_isolation_" +
              std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A small, quick experiment over `techniques`: a 3×3 sphere grid at 64×48,
// 16 spp, two timed frames and no control job.
inline nlohmann::json small_experiment(const nlohmann::json& techniques) {
  return {{"name", "isolation"},
          {"scenes",
           {{{"type", "sphere_grid"},
             {"params", {{"grid", 3}, {"light_size", 0.4}}},
             {"camera", {{"eye", {0.0, 3.5, 5.5}}, {"target", {0.0, 0.6, 0.0}}}}}}},
          {"techniques", techniques},
          {"resolutions", {"64x48"}},
          {"frames", {{"warmup", 0}, {"timed", 2}, {"control", nullptr}}},
          {"reference", {{"spp", 16}}}};
}

inline std::string write_config(const std::filesystem::path& dir, const nlohmann::json& config) {
  const auto path = dir / "config.json";
  std::ofstream(path) << config.dump(2);
  return path.string();
}

// results.jsonl, one JSON value per line.
inline std::vector<nlohmann::json> jsonl_records(const std::filesystem::path& run_dir) {
  std::vector<nlohmann::json> out;
  std::ifstream in(run_dir / "results.jsonl");
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.push_back(nlohmann::json::parse(line));
  return out;
}

inline const nlohmann::json* find_record(const std::vector<nlohmann::json>& records,
                                         const std::string& technique_variant) {
  for (const auto& r : records)
    if (r["technique_variant"] == technique_variant) return &r;
  return nullptr;
}

}  // namespace sb::test
