// `shadowbench run` logs the parameters a technique declares but never reads
// (config/unread_params.h), before the jobs, and runs them all the same.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../config/cli_runner.h"
#include "e2e_util.h"

namespace sb::test {
namespace {

TEST(UnreadParams, RunLogsTheWarningAndRunsTheJob) {
  const std::filesystem::path dir = fresh_test_folder("unread_params_run");
  const nlohmann::json config = {{"name", "unread_run"},
                                 {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 1}}}}}},
                                 {"techniques", {"reads_half"}},
                                 {"resolutions", {{16, 12}}},
                                 {"frames", {{"warmup", 0}, {"timed", 1}}},
                                 {"reference", {{"spp", 1}}}};
  const std::string file = (dir / "unread.json").string();
  std::ofstream(file) << config.dump();
  const CliResult r = run_cli("run " + file + " --quiet --no-images --no-cache --plugins " +
                              UNREAD_PARAM_PLUGIN_DIR + " --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  // file:LINE:COL (/techniques/0): the position is checked in tests/config.
  EXPECT_NE(r.output.find("shadowbench: warning: " + file + ":1:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" (/techniques/0): technique reads_half: parameter 'forgotten'"),
            std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace sb::test
