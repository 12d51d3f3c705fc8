#pragma once
// Runs the shadowbench driver as a user would, capturing output and exit code.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace sb::test {

struct CliResult {
  int exit_code;
  std::string output;  // stdout and stderr (or stdout alone)
};

// Without `with_stderr`, stderr is dropped: for output that is parsed (`plan --json`).
inline CliResult run_cli(const std::string& args, bool with_stderr = true) {
  const std::string cmd =
      std::string(SHADOWBENCH_EXE) + " " + args + (with_stderr ? " 2>&1" : " 2>/dev/null");
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  std::array<char, 512> buf{};
  while (fgets(buf.data(), int(buf.size()), pipe) != nullptr) out += buf.data();
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

}  // namespace sb::test
