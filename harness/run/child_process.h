#pragma once
// One forked child process with two pipes back to the parent: a message
// channel (one line per message) and the child's stderr. The parent reads
// both with a deadline, and can kill the child; the exit is described in
// words ("killed by signal 11 (SIGSEGV: Segmentation fault)").
//
// Fork without exec: the child runs a function of the parent's image. That
// is only safe while the parent has started no thread pool of its own (a
// forked child has only the forking thread, while TBB's and llvmpipe's
// pools would believe theirs still exist), so start() refuses a parent with
// more threads than its libraries started when they were loaded.
#include <sys/types.h>

#include <chrono>
#include <functional>
#include <string>
#include <vector>

namespace sb::run {

class ChildProcess {
 public:
  using Clock = std::chrono::steady_clock;
  // Forks. The child: dies with the parent (PR_SET_PDEATHSIG), has its
  // stderr on the pipe, runs `body(message_fd)` and exits with its return
  // value, never returning here (no atexit handlers, no destructors of the
  // parent's objects). Throws std::runtime_error when the fork fails or the
  // parent has started threads of its own.
  static ChildProcess start(const std::function<int(int message_fd)>& body);

  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&&) = delete;
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess();  // kills and reaps a child still running

  enum class Pumped { Output, Closed, TimedOut };
  // Waits until output arrives, both pipes are closed, or `deadline`; hands
  // over each complete line (without its '\n'). A last line without '\n' is
  // handed over when its pipe closes.
  Pumped pump(Clock::time_point deadline, const std::function<void(const std::string&)>& on_message,
              const std::function<void(const std::string&)>& on_stderr);
  void kill();  // SIGKILL; wait() still reaps it
  int wait();   // the waitpid status; once reaped, the same status again
  pid_t pid() const { return pid_; }

 private:
  ChildProcess(pid_t pid, int message_fd, int stderr_fd)
      : pid_(pid), message_fd_(message_fd), stderr_fd_(stderr_fd) {}
  pid_t pid_ = -1;
  int message_fd_ = -1, stderr_fd_ = -1;
  std::string message_partial_, stderr_partial_;
  bool reaped_ = false;
  int status_ = 0;
};

// The names of this process's threads (/proc/self/task/*/comm).
std::vector<std::string> thread_names();

// A waitpid status in words: "exited with code 3", "killed by signal 11
// (SIGSEGV: Segmentation fault)".
std::string describe_wait_status(int status);
// The signal's name, "SIGSEGV"; "signal 64" for one without.
std::string signal_name(int signal);

// Writes all of `text` to `fd`, retrying after EINTR and short writes;
// false when the reader is gone.
bool write_fully(int fd, const std::string& text);

}  // namespace sb::run
