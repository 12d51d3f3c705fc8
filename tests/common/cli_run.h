#pragma once
// Tests that drive the shadowbench driver as a user would: a command's exit
// code and output, a fresh folder per test, and a run folder's records.
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

// `command` through the shell, stderr with stdout.
inline CliRun run_command(const std::string& command) {
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  CliRun r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), int(buf.size()), pipe) != nullptr) r.output += buf.data();
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// An empty folder named `prefix` + the running test's name.
inline std::filesystem::path test_folder(const std::string& prefix) {
  auto dir = std::filesystem::temp_directory_path() /
             (prefix + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A run folder's results.jsonl, one JSON value per line, in file order.
inline std::vector<nlohmann::json> jsonl_records(const std::filesystem::path& run_dir) {
  std::vector<nlohmann::json> out;
  std::ifstream in(run_dir / "results.jsonl");
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.push_back(nlohmann::json::parse(line));
  return out;
}

}  // namespace sb::test
