#include "run/take_turns.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <stdexcept>

#include "core/error.h"
#include "run/child_process.h"

namespace sb::run {

using core::InputError;

namespace {

// One line without its '\n'; nullopt at end of file before a full line.
std::optional<std::string> read_line(int fd) {
  std::string line;
  char c = 0;
  for (;;) {
    const ssize_t n = ::read(fd, &c, 1);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return std::nullopt;
    if (c == '\n') return line;
    if (line.size() > 4096) return std::nullopt;  // no such line in this protocol
    line += c;
  }
}

int parse_fd(const std::string& text, const std::string& all) {
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || v < 0 || v > 65535)
    throw InputError("", "--take-turns",
                     "expected IN_FD,OUT_FD (two file descriptors), found '" + all + "'");
  return int(v);
}

// The descriptors a started command reads "go" at and writes "ready" to.
constexpr int kChildIn = 3, kChildOut = 4;

// A started command: its pid and our ends of its two pipes.
struct Child {
  pid_t pid = -1;
  int to = -1, from = -1;
  bool running = false;
  int exit_code = 0;
};

int wait_exit_code(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

Child start(const TurnCommand& c) {
  if (c.argv.empty()) throw std::runtime_error(c.label + ": no command");
  std::array<int, 2> to{}, from{};
  if (::pipe2(to.data(), O_CLOEXEC) != 0 || ::pipe2(from.data(), O_CLOEXEC) != 0)
    throw std::runtime_error(c.label + ": pipe: " + std::strerror(errno));
  std::vector<std::string> args = c.argv;
  // The child reads at descriptor 3 and writes at 4, whatever numbers the
  // pipes have here: a process started with descriptors open (some CI
  // runners and IDEs pass them) got pipes above 9, which a POSIX shell
  // cannot name (dash: "exec 3<&41" is "Bad fd number"), so a wrapper
  // script around a build failed.
  args.push_back("--take-turns");
  args.push_back(std::to_string(kChildIn) + "," + std::to_string(kChildOut));
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(c.label + ": fork: " + std::strerror(errno));
  if (pid == 0) {
    // Only the child's own two ends survive exec, at 3 and 4 (every end is
    // O_CLOEXEC, so neither build ever holds the other's pipes open). Both
    // are first copied above 4 (close-on-exec), so that neither dup2 lands
    // on the other end; dup2 clears close-on-exec on 3 and 4.
    const int in = ::fcntl(to[0], F_DUPFD_CLOEXEC, kChildOut + 1);
    const int out = ::fcntl(from[1], F_DUPFD_CLOEXEC, kChildOut + 1);
    if (in < 0 || out < 0 || ::dup2(in, kChildIn) < 0 || ::dup2(out, kChildOut) < 0) {
      std::fprintf(stderr, "shadowbench: %s: cannot place the pipes at 3 and 4: %s\n",
                   c.label.c_str(), std::strerror(errno));
      ::_exit(127);
    }
    ::execv(argv[0], argv.data());
    std::fprintf(stderr, "shadowbench: %s: cannot run %s: %s\n", c.label.c_str(), argv[0],
                 std::strerror(errno));
    ::_exit(127);
  }
  ::close(to[0]);
  ::close(from[1]);
  return {pid, to[1], from[0], true, 0};
}

void finish(Child& c) {
  c.running = false;
  ::close(c.to);
  ::close(c.from);
  c.exit_code = wait_exit_code(c.pid);
}

// Waits for the child's next "ready"; on end of file it has exited.
void await_ready(Child& c, const std::string& label) {
  const auto line = read_line(c.from);
  if (!line) return finish(c);
  if (line->rfind("ready", 0) != 0)
    throw std::runtime_error(label + " broke the turn protocol: it wrote \"" + *line + "\"");
}

}  // namespace

TurnTaker TurnTaker::parse(const std::string& fds) {
  const size_t comma = fds.find(',');
  if (comma == std::string::npos)
    throw InputError("", "--take-turns",
                     "expected IN_FD,OUT_FD (two file descriptors), found '" + fds + "'");
  return {parse_fd(fds.substr(0, comma), fds), parse_fd(fds.substr(comma + 1), fds)};
}

void TurnTaker::take(const std::string& what) const {
  std::string line = "ready " + what;
  for (char& c : line)
    if (c == '\n') c = ' ';
  if (!write_fully(out_, line + "\n"))
    throw std::runtime_error("the driver of --take-turns went away (write failed)");
  const auto reply = read_line(in_);
  if (!reply) throw std::runtime_error("the driver of --take-turns went away");
  if (*reply != "go")
    throw std::runtime_error("--take-turns: expected \"go\" from the driver, read \"" + *reply +
                             "\"");
}

TurnsResult take_turns(const TurnCommand& a, const TurnCommand& b) {
  // A child that exits while we write "go" must not kill the driver.
  struct sigaction ignore {};
  struct sigaction old {};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGPIPE, &ignore, &old);
  const TurnCommand* commands[2] = {&a, &b};
  std::array<Child, 2> children;
  TurnsResult result;
  try {
    for (int i = 0; i < 2; ++i) children[size_t(i)] = start(*commands[i]);
    // Each run says "ready" before it does anything at all.
    for (int i = 0; i < 2; ++i) await_ready(children[size_t(i)], commands[i]->label);
    for (long k = 0; children[0].running || children[1].running; ++k) {
      // ABBA: turns 0 and 3 of every four go to A.
      int i = (k % 4 == 0 || k % 4 == 3) ? 0 : 1;
      if (!children[size_t(i)].running) i = 1 - i;
      Child& c = children[size_t(i)];
      if (!write_fully(c.to, "go\n")) {
        finish(c);
        continue;
      }
      ++result.turns[i];
      await_ready(c, commands[i]->label);
    }
  } catch (...) {
    for (Child& c : children)
      if (c.running) {
        ::kill(c.pid, SIGKILL);
        finish(c);
      }
    ::sigaction(SIGPIPE, &old, nullptr);
    throw;
  }
  ::sigaction(SIGPIPE, &old, nullptr);
  for (int i = 0; i < 2; ++i) result.exit_code[i] = children[size_t(i)].exit_code;
  return result;
}

}  // namespace sb::run
