// The turn protocol of interleaved A/B runs (run/take_turns.h), driven with
// two shell scripts that play a build's part: ABBA order, a build that
// exits early, and one that breaks the protocol.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "run/take_turns.h"

namespace sb {

using run::take_turns;
using run::TurnsResult;

namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("shadowbench_take_turns_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A build's stand-in: says ready, then per "go" logs "<label><block>" and
// says ready again, `blocks` times; then exits. Its last argument is the
// "IN,OUT" that take_turns appends, which must be "3,4": the pipes are at
// descriptors 3 and 4, which every POSIX shell can name (dash names no
// descriptor above 9). POSIX sh only, so that dash runs it.
fs::path write_player(const fs::path& dir, int blocks, const std::string& first_reply = "ready") {
  fs::path script = dir / "player.sh";
  std::ofstream(script)
      << "#!/bin/sh\n"
         "label=$1; log=$2; fds=$5\n"
         "[ \"$fds\" = 3,4 ] || { echo \"pipes at $fds, not 3,4\" >&2; exit 7; }\n"
         "echo '"
      << first_reply
      << " start' >&4\n"
         "i=1\n"
         "while [ $i -le "
      << blocks
      << " ]; do\n"
         "  read go <&3 || exit 9\n"
         "  [ \"$go\" = go ] || exit 8\n"
         "  echo \"$label$i\" >> \"$log\"\n"
         "  [ $i -lt "
      << blocks
      << " ] && echo \"ready block $i\" >&4\n"
         "  i=$((i+1))\n"
         "done\n"
         "exit 0\n";
  fs::permissions(script, fs::perms::owner_all);
  return script;
}

std::string read_all(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(TakeTurns, TurnsGoInAbbaOrderAndOnlyOneBuildRunsAtATime) {
  const fs::path dir = fresh_dir("abba");
  const fs::path player = write_player(dir, 4);
  const std::string log = (dir / "log").string();
  const TurnsResult r = take_turns({"base", {player.string(), "A", log, "unused"}},
                                   {"new", {player.string(), "B", log, "unused"}});
  EXPECT_EQ(r.exit_code[0], 0);
  EXPECT_EQ(r.exit_code[1], 0);
  EXPECT_EQ(r.turns[0], 4);
  EXPECT_EQ(r.turns[1], 4);
  // A writes only while B waits: the log is strictly in turn order.
  EXPECT_EQ(read_all(log), "A1\nB1\nB2\nA2\nA3\nB3\nB4\nA4\n");
}

TEST(TakeTurns, WhenOneBuildHasFinishedTheOtherRunsAlone) {
  const fs::path dir = fresh_dir("alone");
  const fs::path short_player = write_player(dir, 1);
  fs::copy_file(short_player, dir / "short.sh");
  const fs::path long_player = write_player(dir, 3);
  const std::string log = (dir / "log").string();
  const TurnsResult r = take_turns({"base", {(dir / "short.sh").string(), "A", log, "unused"}},
                                   {"new", {long_player.string(), "B", log, "unused"}});
  EXPECT_EQ(r.turns[0], 1);
  EXPECT_EQ(r.turns[1], 3);
  EXPECT_EQ(read_all(log), "A1\nB1\nB2\nB3\n");
  EXPECT_EQ(r.exit_code[0], 0);
  EXPECT_EQ(r.exit_code[1], 0);
}

TEST(TakeTurns, ABuildThatExitsAtOnceIsReportedWithItsExitCode) {
  const fs::path dir = fresh_dir("fails");
  const fs::path failing = dir / "fail.sh";
  std::ofstream(failing) << "#!/bin/sh\nexit 2\n";
  fs::permissions(failing, fs::perms::owner_all);
  const fs::path player = write_player(dir, 2);
  const std::string log = (dir / "log").string();
  const TurnsResult r =
      take_turns({"base", {failing.string()}}, {"new", {player.string(), "B", log, "unused"}});
  EXPECT_EQ(r.exit_code[0], 2);
  EXPECT_EQ(r.turns[0], 0);
  EXPECT_EQ(r.turns[1], 2);
  EXPECT_EQ(read_all(log), "B1\nB2\n");
}

TEST(TakeTurns, ABuildThatBreaksTheProtocolStopsBothWithAnError) {
  const fs::path dir = fresh_dir("garbage");
  const fs::path rude = write_player(dir, 2, "hello");
  fs::copy_file(rude, dir / "rude.sh");
  const fs::path player = write_player(dir, 2);
  const std::string log = (dir / "log").string();
  try {
    take_turns({"base", {(dir / "rude.sh").string(), "A", log, "unused"}},
               {"new", {player.string(), "B", log, "unused"}});
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("base broke the turn protocol"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("hello start"), std::string::npos) << e.what();
  }
}

// Descriptors 3 to 40 open in the driver (some CI runners and IDEs start a
// process so) put the pipes above 9, where dash could not name them: the
// builds still get them at 3 and 4, under each POSIX shell there is.
TEST(TakeTurns, TheBuildsGetThePipesAtThreeAndFourWhateverTheDriverHasOpen) {
  std::vector<int> opened;
  for (int fd = 3; fd <= 40; ++fd)
    if (::fcntl(fd, F_GETFD) < 0) {  // not open: fill it (never close one we did not open)
      const int null = ::open("/dev/null", O_RDONLY);
      ASSERT_GE(null, 0);
      if (null != fd) {
        ASSERT_EQ(::dup2(null, fd), fd);
        ::close(null);
      }
      opened.push_back(fd);
    }
  const fs::path dir = fresh_dir("open_fds");
  const fs::path player = write_player(dir, 2);
  for (const char* shell : {"/bin/sh", "/bin/dash", "/bin/bash", "/bin/busybox"}) {
    if (!fs::exists(shell)) continue;
    std::vector<std::string> prefix = {shell};
    if (fs::path(shell).filename() == "busybox") prefix.push_back("sh");
    auto command = [&](const std::string& label, const std::string& log) {
      std::vector<std::string> argv = prefix;
      for (const std::string& a : {player.string(), label, log, std::string("unused")})
        argv.push_back(a);
      return argv;
    };
    const std::string log = (dir / (fs::path(shell).filename().string() + ".log")).string();
    const TurnsResult r = take_turns({"base", command("A", log)}, {"new", command("B", log)});
    EXPECT_EQ(r.exit_code[0], 0) << shell;
    EXPECT_EQ(r.exit_code[1], 0) << shell;
    EXPECT_EQ(read_all(log), "A1\nB1\nB2\nA2\n") << shell;
  }
  for (const int fd : opened) ::close(fd);
}

TEST(TakeTurns, AMissingBinaryExitsWith127) {
  const fs::path dir = fresh_dir("missing");
  const fs::path player = write_player(dir, 1);
  const TurnsResult r = take_turns({"base", {(dir / "no_such_binary").string()}},
                                   {"new", {player.string(), "B", (dir / "log").string(), "x"}});
  EXPECT_EQ(r.exit_code[0], 127);
  EXPECT_EQ(r.exit_code[1], 0);
}

}  // namespace
}  // namespace sb
