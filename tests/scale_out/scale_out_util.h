#pragma once
// The driver run as a user runs it, into folders named for the running test.
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

}  // namespace sb::test
