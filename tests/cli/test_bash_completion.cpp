// The bash completion that `shadowbench completion bash` prints (and the
// build installs), driven in bash as readline would: COMP_WORDS and
// COMP_CWORD set, the completion function called, COMPREPLY read.
#include <gtest/gtest.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../config/cli_runner.h"
#include "cli/command_line.h"

namespace sb::test {
namespace {

class BashCompletion : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto r = run_cli("completion bash");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    script_ = (std::filesystem::temp_directory_path() /
               ("shadowbench_test_completion-" + std::to_string(::getpid()) + ".bash"))
                  .string();
    std::ofstream(script_) << r.output;
  }

  // The words COMPREPLY holds after completing the last of `words`.
  static std::vector<std::string> complete(const std::vector<std::string>& words) {
    std::string array;
    for (const auto& w : words) array += " '" + w + "'";
    const std::string dir = std::filesystem::temp_directory_path() /
                            ("shadowbench_completion_cwd-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir + "/runs/a");
    std::ofstream(dir + "/quick.json") << "{}";
    std::ofstream(dir + "/notes.txt") << "";
    const std::string command = "cd '" + dir + "' && bash -c 'source " + script_ +
                                " && COMP_WORDS=(" + array +
                                ") && COMP_CWORD=" + std::to_string(words.size() - 1) +
                                " && { _shadowbench; printf \"%s\\n\" \"${COMPREPLY[@]}\"; }'";
    FILE* pipe = popen(command.c_str(), "r");
    std::string out;
    char buf[512];
    while (fgets(buf, sizeof buf, pipe) != nullptr) out += buf;
    pclose(pipe);
    std::vector<std::string> reply;
    std::istringstream lines(out);
    for (std::string line; std::getline(lines, line);)
      if (!line.empty()) reply.push_back(line);
    std::sort(reply.begin(), reply.end());
    return reply;
  }

  static std::string script_;
};
std::string BashCompletion::script_;

using Words = std::vector<std::string>;

TEST_F(BashCompletion, CommandsAndSubcommands) {
  EXPECT_EQ(complete({"shadowbench", "ru"}), Words({"run"}));
  EXPECT_EQ(complete({"shadowbench", "compare"}), Words({"compare", "compare-builds"}));
  EXPECT_EQ(complete({"shadowbench", "scene", ""}), Words({"export", "info"}));
  EXPECT_EQ(complete({"shadowbench", "--ver"}), Words({"--version"}));
  EXPECT_EQ(complete({"shadowbench", "help", "rep"}), Words({"report"}));
}

// Every command the command line registers completes, and after it every
// option it declares: both lists come from the registration, not by hand.
TEST_F(BashCompletion, EveryRegisteredCommandWithItsOptions) {
  cli::CommandLine command_line;
  Words top = {"--help", "--help-all", "--version"};
  for (const CLI::App* c : command_line.app().get_subcommands(nullptr))
    top.push_back(c->get_name());
  std::sort(top.begin(), top.end());
  EXPECT_EQ(complete({"shadowbench", ""}), top);
  for (CLI::App* c : cli::all_commands(command_line.app())) {
    const std::string path = cli::command_path(*c);
    Words words = {"shadowbench"};
    std::istringstream names(path);
    for (std::string name; names >> name;) words.push_back(name);
    const Words named = complete(words);
    EXPECT_NE(std::find(named.begin(), named.end(), c->get_name()), named.end()) << path;
    Words options = {"--help"};
    for (const CLI::Option* o : c->get_options())
      if (!o->get_positional() && !o->get_group().empty() && o->get_lnames()[0] != "help")
        options.push_back("--" + o->get_lnames()[0]);
    std::sort(options.begin(), options.end());
    words.push_back("--");
    EXPECT_EQ(complete(words), options) << path;
  }
}

TEST_F(BashCompletion, EachCommandsOwnOptions) {
  EXPECT_EQ(complete({"shadowbench", "run", "--back"}), Words({"--backend"}));
  EXPECT_EQ(complete({"shadowbench", "compare", "a", "--ti"}),
            Words({"--time-threshold", "--timing"}));
  EXPECT_EQ(complete({"shadowbench", "report", "--ti"}), Words{});  // compare's, not report's
  EXPECT_EQ(complete({"shadowbench", "scene", "export", "--"}), Words({"--help", "--help-all"}));
}

TEST_F(BashCompletion, ChoicesFoldersAndConfigs) {
  EXPECT_EQ(complete({"shadowbench", "run", "--backend", ""}), Words({"egl", "osmesa"}));
  EXPECT_EQ(complete({"shadowbench", "compare-builds", "--normalize", "c"}), Words({"control"}));
  EXPECT_EQ(complete({"shadowbench", "run", "--out", "ru"}), Words({"runs"}));
  EXPECT_EQ(complete({"shadowbench", "run", ""}), Words({"quick.json", "runs"}));
  EXPECT_EQ(complete({"shadowbench", "report", ""}), Words({"runs"}));
}

TEST_F(BashCompletion, TechniqueNamesAndSceneTypes) {
  const Words pcf = complete({"shadowbench", "list", "pcf"});
  EXPECT_FALSE(pcf.empty());
  for (const auto& w : pcf) EXPECT_EQ(w.rfind("pcf", 0), 0u) << w;
  EXPECT_EQ(complete({"shadowbench", "list", "sphere_g"}), Words({"sphere_grid"}));
  EXPECT_EQ(complete({"shadowbench", "list", "heidrich"}), Words({"heidrich_linear"}));
  const Words scenes = complete({"shadowbench", "scene", "info", "jee"});
  EXPECT_EQ(scenes, Words({"jeep"}));
}

}  // namespace
}  // namespace sb::test
