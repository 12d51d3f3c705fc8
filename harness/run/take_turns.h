#pragma once
// Interleaved A/B runs: two builds run the same config on one machine and
// take turns, block of frames by block of frames, so that drift, thermal
// state and noisy neighbours hit both alike (`shadowbench compare-builds`,
// docs/ci.md).
//
// Protocol, one line each way per turn over two pipes: the run writes
// "ready <what>\n" and blocks until the driver writes "go\n". Only one run
// is ever past its "ready": the other is blocked, so nothing it does (not
// even untimed work) overlaps a timed frame.
#include <string>
#include <vector>

namespace sb::run {

// The run's side: `run --take-turns IN_FD,OUT_FD` (take_turns passes 3,4:
// it places the pipes at descriptors 3 and 4 in the child, which any POSIX
// shell can name, whatever numbers they have in the driver).
class TurnTaker {
 public:
  // Throws InputError naming --take-turns for a malformed value.
  static TurnTaker parse(const std::string& fds);
  // Says it is ready and waits for "go". Throws std::runtime_error when the
  // driver went away or wrote something else.
  void take(const std::string& what) const;

 private:
  TurnTaker(int in_fd, int out_fd) : in_(in_fd), out_(out_fd) {}
  int in_ = -1, out_ = -1;
};

// The driver's side: one build's command line.
struct TurnCommand {
  std::string label;              // "base", "new"
  std::vector<std::string> argv;  // argv[0] is the binary; --take-turns is appended
};

struct TurnsResult {
  int exit_code[2] = {0, 0};  // of each command (128 + signal when killed)
  int turns[2] = {0, 0};      // turns given to each
};

// Starts both commands and gives turns in ABBA order (A B B A A B B A ...)
// so neither always goes first; once one has exited the other runs alone.
// Throws std::runtime_error when a command cannot start or breaks the
// protocol (both are then killed).
TurnsResult take_turns(const TurnCommand& a, const TurnCommand& b);

}  // namespace sb::run
