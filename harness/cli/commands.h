#pragma once
// The commands, one file each (cmd_*.cpp): each adds its subcommand to the
// command line with its arguments and options, parsed into a struct of its
// own, and the action that runs it. command_line.cpp registers them in the
// order --help, docs/cli.md and the completion list them.
namespace sb::cli {

class CommandLine;

void add_run_command(CommandLine& cl);
void add_validate_command(CommandLine& cl);
void add_plan_command(CommandLine& cl);
void add_merge_command(CommandLine& cl);
void add_list_command(CommandLine& cl);
void add_report_command(CommandLine& cl);
void add_compare_command(CommandLine& cl);
void add_compare_builds_command(CommandLine& cl);
void add_scene_commands(CommandLine& cl);    // scene export, scene info
void add_history_commands(CommandLine& cl);  // history add, history report
void add_new_technique_command(CommandLine& cl);
void add_check_technique_command(CommandLine& cl);
void add_help_command(CommandLine& cl);
void add_completion_command(CommandLine& cl);

}  // namespace sb::cli
