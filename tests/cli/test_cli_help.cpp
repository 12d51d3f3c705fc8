// Every command's --help prints its own options, their defaults and an
// example, checked against the parser itself; docs/cli.md is the parser's
// snapshot (`shadowbench help --markdown`), so an option added, removed or
// changed without the docs fails here.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <fstream>
#include <set>
#include <sstream>

#include "../config/cli_runner.h"
#include "cli/command_line.h"

namespace sb::test {
namespace {

std::string long_name(const CLI::Option* o) {
  return o->get_lnames().empty() ? "" : "--" + o->get_lnames()[0];
}

TEST(CliHelp, EveryCommandPrintsItsOwnOptionsDefaultsAndAnExample) {
  cli::CommandLine command_line;
  const auto commands = cli::all_commands(command_line.app());
  ASSERT_GE(commands.size(), 12u);  // run ... completion, scene export and info
  std::set<std::string> every_option;
  for (CLI::App* c : commands)
    for (const CLI::Option* o : c->get_options()) every_option.insert(long_name(o));
  for (CLI::App* c : commands) {
    const std::string path = cli::command_path(*c);
    const auto r = run_cli(path + " --help");
    ASSERT_EQ(r.exit_code, 0) << path << "\n" << r.output;
    EXPECT_NE(r.output.find("Usage: shadowbench " + path), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c->get_description().substr(0, 40)), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("Example:\n  shadowbench "), std::string::npos) << r.output;
    std::set<std::string> own;
    for (const CLI::Option* o : c->get_options()) {
      own.insert(long_name(o));
      if (o->get_group().empty()) {  // hidden: --take-turns
        EXPECT_EQ(r.output.find(long_name(o)), std::string::npos)
            << path << " shows " << long_name(o);
        continue;
      }
      const std::string name = o->get_positional() ? o->get_name(true) : long_name(o);
      EXPECT_NE(r.output.find(name), std::string::npos) << path << " lacks " << name;
      if (!o->get_positional() && o->get_type_size() > 0 && !o->get_default_str().empty()) {
        EXPECT_NE(r.output.find(name + " " + o->get_type_name() + "=" + o->get_default_str()),
                  std::string::npos)
            << path << ": " << name << " without its default " << o->get_default_str() << "\n"
            << r.output;
      }
    }
    // No other command's option leaks into this one's help.
    for (const std::string& other : every_option) {
      if (!other.empty() && own.count(other) == 0) {
        EXPECT_EQ(r.output.find(other + " "), std::string::npos) << path << " shows " << other;
      }
    }
  }
}

TEST(CliHelp, SpecificOptionsAndDefaults) {
  const auto run = run_cli("run --help");
  for (const char* expected :
       {"--backend {osmesa,egl}=osmesa", "--cache-dir DIR=results/cache", "--max-jobs N=10000",
        "--pass-timing {coarse,fine}=coarse", "--no-images", "--out DIR",
        "--isolation {group,job,none}=group", "--job-timeout SECONDS"})
    EXPECT_NE(run.output.find(expected), std::string::npos) << expected << "\n" << run.output;
  const auto compare = run_cli("compare --help");
  for (const char* expected :
       {"--alpha A=0.02", "--time-threshold R=0.1", "--error-threshold E=0.005",
        "--normalize {none,control}=none", "--timing {frame,technique,none}=frame",
        "--metric PATH=visibility.geometry.rmse", "BASE_DIR", "NEW_DIR"})
    EXPECT_NE(compare.output.find(expected), std::string::npos) << expected << "\n"
                                                                << compare.output;
  // compare-builds judges ratios to the control job by default.
  EXPECT_NE(run_cli("compare-builds --help").output.find("--normalize {none,control}=control"),
            std::string::npos);
  EXPECT_EQ(run_cli("help report").output, run_cli("report --help").output);
}

TEST(CliHelp, TheReferenceIsTheParsersSnapshot) {
  std::ifstream in(std::string(SHADOWBENCH_SOURCE_DIR) + "/docs/cli.md");
  std::stringstream file;
  file << in.rdbuf();
  const auto r = run_cli("help --markdown");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(file.str(), r.output)
      << "regenerate it: build/shadowbench help --markdown > docs/cli.md";
  // Every visible option of every command is in it, under its command.
  cli::CommandLine command_line;
  for (CLI::App* c : cli::all_commands(command_line.app())) {
    const size_t section = r.output.find("\n## " + cli::command_path(*c) + "\n");
    ASSERT_NE(section, std::string::npos) << cli::command_path(*c);
    const size_t end = r.output.find("\n## ", section + 4);
    const std::string body = r.output.substr(section, end - section);
    for (const CLI::Option* o : c->get_options()) {
      if (!o->get_group().empty() && long_name(o) != "--help" && long_name(o) != "--help-all" &&
          !o->get_positional()) {
        EXPECT_NE(body.find("| `" + long_name(o) + "` |"), std::string::npos)
            << cli::command_path(*c) << " " << long_name(o);
      }
    }
  }
}

TEST(CliHelp, VersionSaysTheVersionTheCommitAndTheBackends) {
  const auto r = run_cli("--version");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.rfind("shadowbench " SHADOWBENCH_TEST_VERSION " (git ", 0), 0u) << r.output;
  EXPECT_NE(r.output.find("GL backends: osmesa"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("plugins: " SHADOWBENCH_PLUGIN_DIR), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("data: " SHADOWBENCH_BINARY_DIR "/share/shadowbench"), std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace sb::test
