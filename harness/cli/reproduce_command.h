#pragma once
// The command that reruns one job of this `run` in this process, under gdb,
// for a job whose process crashed or hung (run/isolated_work.h): this
// process's own arguments without those that choose the jobs or their
// processes (--only, --isolation, --job-timeout, --take-turns), then
// --only 'ID' --isolation none, and --out DIR when the run chose its folder.
// Kept otherwise as typed, relative paths and all: it is run from the same
// folder, and so renders the job as the run did (same config, plugins,
// reference options, shard).
#include <string>
#include <vector>

namespace sb::cli {

// This process's arguments, argv[0] first (/proc/self/cmdline); empty when
// they cannot be read.
std::vector<std::string> own_arguments();

// "gdb --args <arguments...> --only 'ID' --isolation none", each argument
// quoted for a POSIX shell where it needs to be.
std::string reproduce_command(const std::vector<std::string>& arguments, const std::string& run_dir,
                              const std::string& job_id);

// `text` as one word of a POSIX shell: as is when it is plain, else in
// single quotes.
std::string shell_word(const std::string& text);

}  // namespace sb::cli
