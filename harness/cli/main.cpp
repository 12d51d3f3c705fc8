// shadowbench — the command-line driver: parse (cli/command_line.h), then
// run the command chosen (cli/commands.h). `shadowbench --help` and
// docs/cli.md say what each command takes.
// Exit codes: 0 all jobs ok or skipped, 1 some job failed, 2 bad input
// (config, arguments), 3 environment (no GL context, missing plugins; for
// validate and plan, a plugin the config needs failed to load),
// 4 (compare) a significant regression over threshold; compare exits 2 too
// when it could not compare some job's time (other hosts, no control).
#include <cstdio>

#include "cli/command_line.h"
#include "core/error.h"

int main(int argc, char** argv) {
  sb::cli::CommandLine command_line;
  try {
    if (const int code = command_line.parse(argc, argv); code >= 0) return code;
    return command_line.run();
  } catch (const sb::core::InputError& e) {
    std::fprintf(stderr, "shadowbench: error: %s\n", e.what());
    return sb::core::kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "shadowbench: internal error: %s\n", e.what());
    return sb::core::kExitInternal;
  }
}
