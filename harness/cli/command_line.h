#pragma once
// The command line, on CLI11: every subcommand with its own options, their
// defaults and one example in its --help; --version; and errors in the
// harness's words with exit code 2, naming the option (docs/cli.md is
// generated from this parser, and a test keeps the two equal). Each command
// file (cmd_*.cpp, cli/commands.h) declares its subcommand, its options and
// the struct they are parsed into; command_line.cpp registers them.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace sb::cli {

// The App is deleted in command_line.cpp, so that holding one needs no
// <CLI/CLI.hpp>, whose App emits its inline virtual functions wherever it
// is destroyed: main.cpp took 13.1 CPU s at -O3 with it, 5.3 s without
// (Release, 2-core VM under load).
struct AppDeleter {
  void operator()(CLI::App* app) const;
};
using AppPtr = std::unique_ptr<CLI::App, AppDeleter>;

// What a command does with its parsed arguments: returns the exit code, and
// throws bad input as core::InputError, which main() prints with exit code 2.
using CommandAction = std::function<int()>;

// The parser with every command registered, and each command's action.
class CommandLine {
 public:
  CommandLine();
  ~CommandLine();
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  CLI::App& app() { return *app_; }

  // A command under `parent` (the app, or a command of subcommands) with
  // one example in its help, and what runs it (none for a command of
  // subcommands). Its options are the caller's to add.
  CLI::App* add_command(CLI::App& parent, const std::string& name, const std::string& description,
                        const std::string& example, CommandAction action = {});

  // Parses argv. Returns -1 to go on with run(), or the exit code to end
  // with: 0 after --help or --version (printed to stdout), 2 after a usage
  // error (printed to stderr as "shadowbench: error: ...").
  int parse(int argc, const char* const* argv);

  // Runs the command parse() chose and returns its exit code.
  int run() const;

 private:
  std::map<const CLI::App*, CommandAction> actions_;
  const CLI::App* chosen_ = nullptr;
  AppPtr app_;  // after actions_: destroyed first, as it refers to their arguments
};

// Every subcommand, depth first, as "run", "scene export", ...; for the
// reference, completion and tests.
std::vector<CLI::App*> all_commands(CLI::App& app);
std::string command_path(const CLI::App& command);

}  // namespace sb::cli
