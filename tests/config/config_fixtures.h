#pragma once
// What the config tests share: the shipped plugins' registry
// (tests/plan/test_registry.h), and config files written to a temporary
// folder of the test's own.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/plan/test_registry.h"

namespace sb::test {

// Writes `text` to <temp>/<folder>-<pid>/<name>; returns the path. The
// process id keeps the shards of one test executable, which ctest runs side
// by side, out of each other's files.
inline std::string write_temp(const std::string& folder, const std::string& name,
                              const std::string& text) {
  const auto dir =
      std::filesystem::temp_directory_path() / (folder + "-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace sb::test
