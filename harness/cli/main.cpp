// shadowbench — the command-line driver: parse (cli/command_line.h), then
// run one command (cli/commands.h). `shadowbench --help` and docs/cli.md say
// what each command takes.
// Exit codes: 0 all jobs ok or skipped, 1 some job failed, 2 bad input
// (config, arguments), 3 environment (no GL context, missing plugins; for
// validate and plan, a plugin the config needs failed to load),
// 4 (compare) a significant regression over threshold; compare exits 2 too
// when it could not compare some job's time (other hosts, no control).
#include <cstdio>

#include "cli/command_line.h"
#include "cli/commands.h"
#include "core/error.h"

int main(int argc, char** argv) {
  using namespace sb;
  using namespace sb::cli;
  Args a;
  const AppPtr app = make_command_line(a);
  try {
    if (const int code = parse_command_line(*app, argc, argv, a); code >= 0) return code;
    if (a.command == "run") return cmd_run(a);
    if (a.command == "validate") return cmd_validate(a, false);
    if (a.command == "plan") return cmd_validate(a, true);
    if (a.command == "list") return cmd_list(a);
    if (a.command == "report") return cmd_report(a);
    if (a.command == "compare") return cmd_compare(a);
    if (a.command == "merge") return cmd_merge(a);
    if (a.command == "compare-builds") return cmd_compare_builds(a);
    if (a.command == "scene export") return cmd_scene_export(a);
    if (a.command == "scene info") return cmd_scene_info(a);
    if (a.command == "history add") return cmd_history_add(a);
    if (a.command == "history report") return cmd_history_report(a);
    if (a.command == "new-technique") return cmd_new_technique(a);
    if (a.command == "help") return cmd_help(a, *app);
    if (a.command == "completion") return cmd_completion(a, *app);
    std::fprintf(stderr, "shadowbench: internal error: no handler for '%s'\n", a.command.c_str());
    return sb::core::kExitInternal;
  } catch (const sb::core::InputError& e) {
    std::fprintf(stderr, "shadowbench: error: %s\n", e.what());
    return sb::core::kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "shadowbench: internal error: %s\n", e.what());
    return sb::core::kExitInternal;
  }
}
