#pragma once
// The driver run as a user runs it, with the test-only fault plugin on
// $SHADOWBENCH_PLUGIN_PATH, into folders of the running test's name.
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../common/cli_run.h"

namespace sb::test {

inline std::string shadowbench_command(const std::string& args) {
  return "SHADOWBENCH_PLUGIN_PATH='" FAULT_PLUGIN_DIR "' '" SHADOWBENCH_EXE "' " + args;
}

inline CliRun run_shadowbench(const std::string& args) {
  return run_command(shadowbench_command(args));
}

// An empty folder named for the running test.
inline std::filesystem::path test_folder() { return test_folder("sb_isolation_"); }

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

inline const nlohmann::json* find_record(const std::vector<nlohmann::json>& records,
                                         const std::string& technique_variant) {
  for (const auto& r : records)
    if (r["technique_variant"] == technique_variant) return &r;
  return nullptr;
}

}  // namespace sb::test
