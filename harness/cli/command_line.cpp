#include "cli/command_line.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <utility>

#include "cli/commands.h"
#include "cli/version.h"
#include "core/error.h"

namespace sb::cli {

using core::kExitBadInput;
using core::kExitInternal;

namespace {

// Every command, in the order --help, docs/cli.md and the completion list
// them; each file adds its own options (cli/commands.h).
constexpr void (*kCommands[])(CommandLine&) = {
    add_run_command,      add_validate_command,       add_plan_command,
    add_merge_command,    add_list_command,           add_report_command,
    add_compare_command,  add_compare_builds_command, add_scene_commands,
    add_history_commands, add_new_technique_command,  add_check_technique_command,
    add_help_command,     add_completion_command};

// --help-all (and so the man page help2man makes from it): each command
// under a heading of its own, "shadowbench run:", at the first column, then
// its description and its arguments and options indented, with no group
// headings of their own, so help2man sets one subsection per command.
class ExpandedFormatter : public CLI::Formatter {
 public:
  std::string make_expanded(const CLI::App* sub) const override {
    std::string body = make_positionals(sub) + make_groups(sub, CLI::AppFormatMode::Sub);
    std::string options;
    size_t start = 0;
    while (start < body.size()) {
      const size_t end = std::min(body.find('\n', start), body.size());
      const std::string line = body.substr(start, end - start);
      const bool heading = !line.empty() && line[0] != ' ' && line.back() == ':';
      if (!line.empty() && !heading) options += "  " + line + "\n";
      start = end + 1;
    }
    std::string out =
        "\nshadowbench " + command_path(*sub) + ":\n  " + sub->get_description() + "\n\n" + options;
    for (const CLI::App* c : sub->get_subcommands({})) out += make_expanded(c);
    return out;
  }

  std::string make_subcommands(const CLI::App* app, CLI::AppFormatMode mode) const override {
    if (mode != CLI::AppFormatMode::All) return CLI::Formatter::make_subcommands(app, mode);
    std::string out;
    for (const CLI::App* c : app->get_subcommands({})) out += make_expanded(c);
    return out;
  }
};

// The options of every command but `from`, as "--alpha" -> "compare, compare-builds".
std::string commands_taking(CLI::App& app, const std::string& option, const CLI::App* from) {
  std::vector<std::string> takers;
  for (CLI::App* c : all_commands(app)) {
    if (c == from) continue;
    for (const CLI::Option* o : c->get_options())
      if (!o->get_lnames().empty() && "--" + o->get_lnames()[0] == option &&
          !o->get_group().empty())
        takers.push_back(command_path(*c));
  }
  std::string text;
  for (size_t i = 0; i < takers.size(); ++i)
    text += (i == 0 ? "" : i + 1 == takers.size() ? " or " : ", ") + takers[i];
  return text;
}

}  // namespace

std::string command_path(const CLI::App& command) {
  std::vector<std::string> names = {command.get_name()};
  for (const CLI::App* p = command.get_parent(); p != nullptr && p->get_parent() != nullptr;
       p = p->get_parent())
    names.insert(names.begin(), p->get_name());
  std::string path;
  for (const std::string& n : names) path += (path.empty() ? "" : " ") + n;
  return path;
}

std::vector<CLI::App*> all_commands(CLI::App& app) {
  std::vector<CLI::App*> out;
  for (CLI::App* c : app.get_subcommands(nullptr)) {
    out.push_back(c);
    for (CLI::App* d : all_commands(*c)) out.push_back(d);
  }
  return out;
}

void AppDeleter::operator()(CLI::App* app) const { delete app; }

CommandLine::CommandLine() {
  app_.reset(new CLI::App(
      "shadowbench: a headless batch benchmark of shadow-rendering techniques. It renders every "
      "technique variant of a JSON experiment at every resolution, times each pass, and "
      "measures each one against a ray-traced reference.",
      "shadowbench"));
  CLI::App* app = app_.get();
  app->name("shadowbench");
  app->option_defaults()->always_capture_default();
  app->set_help_flag("-h,--help", "print this help and exit");
  app->formatter(std::make_shared<ExpandedFormatter>());
  app->get_formatter()->column_width(34);
  app->require_subcommand(1);
  app->allow_extras();
  app->set_help_all_flag("--help-all", "print the help of every command");
  app->set_version_flag("--version", version_text,
                        "print the version, git describe, the GL backends built and the "
                        "folders plugins and data are found in");
  app->footer(
      "`shadowbench COMMAND --help` prints a command's options.\n"
      "Exit codes: 0 every job ok or skipped, 1 some job failed (the others' results are kept), "
      "2 bad input or usage (the message names the file and the place in it, or the option), "
      "3 environment (no GL context, no plugins, run folder in use; validate and plan: a plugin "
      "CONFIG needs failed to load), 4 compare found a regression.");

  for (void (*add)(CommandLine&) : kCommands) add(*this);
}

CommandLine::~CommandLine() = default;

CLI::App* CommandLine::add_command(CLI::App& parent, const std::string& name,
                                   const std::string& description, const std::string& example,
                                   CommandAction action) {
  CLI::App* sub = parent.add_subcommand(name, description);
  sub->group("Commands");
  sub->footer("Example:\n  " + example);
  // Unknown options are collected and reported by parse(), which can say
  // which other command takes them.
  sub->allow_extras();
  if (action) actions_[sub] = std::move(action);
  return sub;
}

int CommandLine::parse(int argc, const char* const* argv) {
  CLI::App& app = *app_;
  auto usage_error = [](const std::string& message, const std::string& hint) {
    std::fprintf(stderr, "shadowbench: error: %s\n%s\n", message.c_str(), hint.c_str());
    return int(kExitBadInput);
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // The deepest command named so far says where to look.
    CLI::App* deepest = &app;
    while (!deepest->get_subcommands().empty()) deepest = deepest->get_subcommands().front();
    const std::string where =
        deepest == &app ? "shadowbench" : "shadowbench " + command_path(*deepest);
    if (dynamic_cast<const CLI::RequiredError*>(&e) != nullptr &&
        deepest->get_require_subcommand_min() > 0) {
      // A command without its subcommand: name what was given instead, and
      // say which there are.
      std::string choices;
      for (const CLI::App* c : deepest->get_subcommands(nullptr))
        choices += (choices.empty() ? "" : ", ") + c->get_name();
      const std::vector<std::string> extra = deepest->remaining();
      const std::string what = deepest == &app ? "command" : command_path(*deepest) + " command";
      if (!extra.empty() && extra.front().rfind('-', 0) == 0)
        return usage_error(
            "unknown option '" + extra.front() + "'; expected a " + what + " (" + choices + ")",
            "(see " + where + " --help)");
      return usage_error(
          (extra.empty() ? "expected a " + what : "unknown " + what + " '" + extra.front() + "'") +
              " (" + choices + ")",
          "(see " + where + " --help)");
    }
    return usage_error(e.what(), "(see " + where + " --help)");
  }
  CLI::App* command = &app;
  while (!command->get_subcommands().empty()) command = command->get_subcommands().front();
  // Arguments no command took: an unknown option, a misplaced one, or one
  // argument too many. The deepest command with one is named.
  CLI::App* with_extra = command;
  while (with_extra != nullptr && with_extra->remaining().empty())
    with_extra = with_extra->get_parent();
  if (with_extra != nullptr) {
    const std::string arg = with_extra->remaining().front();
    const std::string name = with_extra == &app ? std::string() : command_path(*with_extra);
    const std::string hint = "(see shadowbench " + (name.empty() ? "" : name + " ") + "--help)";
    if (arg.rfind('-', 0) != 0) {
      if (with_extra == &app) return usage_error("unknown command '" + arg + "'", hint);
      return usage_error("unexpected argument '" + arg + "' for " + name, hint);
    }
    const std::string option = arg.substr(0, arg.find('='));
    if (const std::string takers = commands_taking(app, option, with_extra); !takers.empty())
      return usage_error(option + " goes with " + takers + ", not with " + name, hint);
    return usage_error("unknown option '" + option + "'" + (name.empty() ? "" : " for " + name),
                       hint);
  }
  chosen_ = command;
  return -1;
}

int CommandLine::run() const {
  const auto it = actions_.find(chosen_);
  if (it != actions_.end()) return it->second();
  const std::string path = chosen_ == nullptr ? "" : command_path(*chosen_);
  std::fprintf(stderr, "shadowbench: internal error: no handler for '%s'\n", path.c_str());
  return kExitInternal;
}

}  // namespace sb::cli
