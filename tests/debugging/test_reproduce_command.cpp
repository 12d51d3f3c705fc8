// The command a crashed job's reason suggests: the run's own arguments,
// without those that choose jobs or processes, then this job in-process.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli/reproduce_command.h"

namespace sb::cli {
namespace {

TEST(ReproduceCommand, KeepsTheRunsArgumentsAndRunsTheOneJobInProcess) {
  const std::vector<std::string> args = {"./build/shadowbench",
                                         "run",
                                         "my dir/small.json",
                                         "--out",
                                         "r1",
                                         "--isolation",
                                         "job",
                                         "--only",
                                         "*pcss*",
                                         "--job-timeout=60",
                                         "--no-cache",
                                         "--only=other*",
                                         "--shard",
                                         "1/2"};
  EXPECT_EQ(reproduce_command(args, "r1", "sphere_grid__96x72__my_pcf--k=3"),
            "gdb --args ./build/shadowbench run 'my dir/small.json' --out r1 --no-cache --shard "
            "1/2 --only 'sphere_grid__96x72__my_pcf--k=3' --isolation none");
}

TEST(ReproduceCommand, NamesTheRunFolderTheRunChoseItself) {
  EXPECT_EQ(reproduce_command({"shadowbench", "run", "c.json"}, "results/c-20261207T1500Z", "j"),
            "gdb --args shadowbench run c.json --out results/c-20261207T1500Z --only 'j' "
            "--isolation none");
  EXPECT_EQ(reproduce_command({"shadowbench", "run", "c.json", "--out=x"}, "x", "j"),
            "gdb --args shadowbench run c.json --out=x --only 'j' --isolation none");
}

TEST(ReproduceCommand, QuotesWordsAsAPosixShellReadsThem) {
  EXPECT_EQ(shell_word("plain/path-1.json"), "plain/path-1.json");
  EXPECT_EQ(shell_word("a b"), "'a b'");
  EXPECT_EQ(shell_word("it's"), "'it'\\''s'");
  EXPECT_EQ(shell_word("$HOME"), "'$HOME'");
  EXPECT_EQ(shell_word(""), "''");
}

}  // namespace
}  // namespace sb::cli
