#pragma once
// A plugin folder as a user might break it: random bytes named .so, a
// module with a symbol nothing defines (my_pcf.so), and one registering a
// technique a shipped plugin has (half_registered.so); plus configs to run.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "../common/cli_run.h"

namespace sb::test {

inline std::filesystem::path broken_plugin_folder() {
  std::filesystem::path dir = test_folder("sb_broken_plugins_");
  std::mt19937 bytes(41);
  std::ofstream corrupt(dir / "corrupt.so", std::ios::binary);
  for (int i = 0; i < 4096; ++i) corrupt.put(static_cast<char>(bytes() & 0xff));
  corrupt.close();
  for (const char* module : {"my_pcf.so", "half_registered.so"})
    std::filesystem::copy_file(std::filesystem::path(BROKEN_PLUGIN_DIR) / module, dir / module);
  return dir;
}

// A config of `techniques` (a JSON list) on a small sphere grid, written to `dir`.
inline std::string small_config(const std::filesystem::path& dir, const std::string& techniques) {
  const std::filesystem::path path = dir / "config.json";
  std::ofstream(path)
      << R"({"name": "broken", "scenes": [{"type": "sphere_grid", "params": {"grid": 2}}],
    "techniques": )"
      << techniques << R"(, "resolutions": [[32, 24]],
    "frames": {"warmup": 0, "timed": 1}, "reference": {"spp": 4}})";
  return path.string();
}

// `shadowbench ARGS` with $SHADOWBENCH_PLUGIN_PATH set to `path` ("": unset).
inline CliRun shadowbench(const std::string& path, const std::string& args) {
  const std::string env = path.empty() ? "env -u SHADOWBENCH_PLUGIN_PATH "
                                       : "env SHADOWBENCH_PLUGIN_PATH=" + path + " ";
  return run_command(env + SHADOWBENCH_EXE + " " + args);
}

}  // namespace sb::test
