// Usage errors: exit code 2, on stderr, naming the option or argument, and
// where it belongs when another command takes it.
#include <gtest/gtest.h>

#include "../config/cli_runner.h"

namespace sb::test {
namespace {

TEST(CliErrors, AnUnknownOptionExitsTwoAndNamesIt) {
  struct {
    const char* args;
    const char* message;
  } cases[] = {
      {"run x.json --frobnicate", "unknown option '--frobnicate' for run"},
      {"run x.json --frobnicate=3", "unknown option '--frobnicate' for run"},
      {"scene export --frobnicate", "unknown option '--frobnicate' for scene export"},
      {"--frobnicate", "unknown option '--frobnicate'"},
      {"frobnicate", "unknown command 'frobnicate'"},
      {"scene frobnicate", "unknown scene command 'frobnicate' (export, info)"},
      {"", "expected a command (run, validate"},
      {"report r --alpha 0.1", "--alpha goes with compare or compare-builds, not with report"},
      {"plan x.json --out o",
       "--out goes with run, report, compare-builds or history report, not with plan"},
      {"compare a b c", "unexpected argument 'c' for compare"},
  };
  for (const auto& c : cases) {
    const auto r = run_cli(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(std::string("shadowbench: error: ") + c.message), std::string::npos)
        << c.args << "\n"
        << r.output;
    EXPECT_NE(r.output.find("--help)"), std::string::npos) << "no pointer to the help\n"
                                                           << r.output;
  }
}

TEST(CliErrors, ABadValueExitsTwoAndNamesTheOption) {
  struct {
    const char* args;
    const char* message;
  } cases[] = {
      {"run x.json --backend vulkan", "--backend: expected osmesa or egl, found 'vulkan'"},
      {"run x.json --pass-timing all", "--pass-timing: expected coarse or fine, found 'all'"},
      {"run x.json --max-jobs 1.5",
       "--max-jobs: expected a whole number in [1, 1e12], found '1.5'"},
      {"validate x.json --max-jobs 0", "--max-jobs: expected a whole number"},
      {"run x.json --turn-block -2", "--turn-block: expected a whole number of frames"},
      {"run x.json --embree-config isa=avx3", "--embree-config: "},
      {"run x.json --isolation process",
       "--isolation: expected group, job or none, found 'process'"},
      {"run x.json --job-timeout 0", "--job-timeout: expected a number of seconds in [1, 604800]"},
      {"run x.json --job-timeout soon", "--job-timeout: expected a number of seconds"},
      {"compare a b --alpha x", "--alpha: expected a number, found 'x'"},
      {"compare a b --timing shading", "--timing: expected frame, technique or none"},
      {"compare a b --normalize ratio", "--normalize: expected none or control, found 'ratio'"},
      {"run x.json --out", "--out: 1 required DIR missing"},
      {"completion zsh", "expected the shell 'bash', found 'zsh'"},
      {"help nothing", "no command 'nothing'"},
      {"list no_such_technique", "list no_such_technique: no technique or scene type"},
  };
  for (const auto& c : cases) {
    const auto r = run_cli(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << "\n" << r.output;
  }
}

TEST(CliErrors, HelpAndVersionWinOverOtherArguments) {
  EXPECT_EQ(run_cli("run --help --frobnicate").exit_code, 0);
  EXPECT_EQ(run_cli("--version").exit_code, 0);
  EXPECT_EQ(run_cli("--help").exit_code, 0);
  EXPECT_EQ(run_cli("--help-all").exit_code, 0);
}

}  // namespace
}  // namespace sb::test
