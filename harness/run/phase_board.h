#pragma once
// Where a job in a child process is (prepare(), a frame's render(),
// read-back, ...), for the reason of a job whose process died: "crashed in
// prepare(): ...". One line of text in memory the parent and its forked
// child share, written by the child before each phase and read by the
// parent once the child has gone. A write is a copy into memory: no
// system call and no wake-up of the parent, so phases may be said between
// timed frames.
#include <string>
#include <string_view>

namespace sb::run {

class PhaseBoard {
 public:
  // Maps the shared page: make it before the fork. Throws std::runtime_error
  // when it cannot be mapped.
  PhaseBoard();
  ~PhaseBoard();
  PhaseBoard(const PhaseBoard&) = delete;
  PhaseBoard& operator=(const PhaseBoard&) = delete;

  // The child: the phase it enters (cut to the board's size); "" for none.
  void set(std::string_view phase);
  // The parent, once the child has gone: the last phase set.
  std::string read() const;

 private:
  char* text_ = nullptr;
};

}  // namespace sb::run
