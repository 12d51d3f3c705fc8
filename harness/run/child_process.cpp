#include "run/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "core/lazy_library.h"

namespace sb::run {

namespace {

void close_fd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

// Reads what `fd` has; complete lines go to `take`. False at end of file.
bool read_lines(int& fd, std::string& partial,
                const std::function<void(const std::string&)>& take) {
  std::array<char, 65536> buf{};
  const ssize_t n = ::read(fd, buf.data(), buf.size());
  if (n < 0 && (errno == EINTR || errno == EAGAIN)) return true;
  if (n <= 0) {
    if (!partial.empty()) take(partial);
    partial.clear();
    close_fd(fd);
    return false;
  }
  partial.append(buf.data(), size_t(n));
  size_t begin = 0;
  for (size_t nl = partial.find('\n'); nl != std::string::npos; nl = partial.find('\n', begin)) {
    take(partial.substr(begin, nl - begin));
    begin = nl + 1;
  }
  partial.erase(0, begin);
  return true;
}

[[noreturn]] void run_child(const std::function<int(int)>& body, pid_t parent, int message_fd,
                            int stderr_fd) {
  // A parent killed with SIGKILL takes its child along: no orphan holds the
  // run folder's lock or keeps rendering.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(127);
  ::dup2(stderr_fd, STDERR_FILENO);
  ::close(stderr_fd);
  int code = 0;
  try {
    code = body(message_fd);
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "shadowbench: child process: %s\n", ex.what());
    code = 70;
  } catch (...) {
    code = 70;
  }
  std::fflush(stdout);
  std::fflush(stderr);
  ::_exit(code);
}

// Threads that run before any of ours: libraries' load-time pools. Debian's
// log4cplus, which OpenImageIO's dependencies bring in, starts four idle
// workers when it is loaded. A child never calls into such a library and
// leaves with _exit(), which runs no destructor that would join them. This
// library is loaded after its dependencies, so the count includes theirs.
size_t threads_at_load();

}  // namespace

std::vector<std::string> thread_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator("/proc/self/task", ec);
       !ec && it != std::filesystem::directory_iterator(); it.increment(ec)) {
    std::ifstream in(it->path() / "comm");
    std::string name;
    std::getline(in, name);
    names.push_back(name);
  }
  return names;
}

namespace {
const size_t kThreadsAtLoad = thread_names().size();
size_t threads_at_load() { return kThreadsAtLoad; }
}  // namespace

ChildProcess ChildProcess::start(const std::function<int(int)>& body) {
  // Libraries loaded on first use (core/lazy_library.h) may have started
  // theirs since: OpenImageIO's, when the plan decoded a glTF texture.
  const size_t not_ours = threads_at_load() + core::threads_started_by_lazy_libraries();
  if (const auto threads = thread_names(); threads.size() > not_ours) {
    std::string list;
    for (const auto& t : threads) list += (list.empty() ? "" : ", ") + t;
    throw std::runtime_error(
        "cannot isolate jobs in child processes: this process runs " +
        std::to_string(threads.size()) + " threads (" + list + "), more than the " +
        std::to_string(not_ours) +
        " its libraries started when loaded, and a forked child would inherit their state "
        "but not the threads; use --isolation none");
  }
  std::array<int, 2> message{-1, -1}, err{-1, -1};
  if (::pipe2(message.data(), O_CLOEXEC) != 0 || ::pipe2(err.data(), O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("cannot create a pipe: ") + std::strerror(errno));
  // Whatever the parent has buffered would otherwise be written twice.
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    for (int fd : {message[0], message[1], err[0], err[1]}) ::close(fd);
    throw std::runtime_error(std::string("cannot fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    ::close(message[0]);
    ::close(err[0]);
    run_child(body, parent, message[1], err[1]);
  }
  ::close(message[1]);
  ::close(err[1]);
  return {pid, message[0], err[0]};
}

ChildProcess::ChildProcess(ChildProcess&& other) noexcept
    : pid_(other.pid_),
      message_fd_(other.message_fd_),
      stderr_fd_(other.stderr_fd_),
      message_partial_(std::move(other.message_partial_)),
      stderr_partial_(std::move(other.stderr_partial_)),
      reaped_(other.reaped_),
      status_(other.status_) {
  other.pid_ = -1;
  other.message_fd_ = other.stderr_fd_ = -1;
}

ChildProcess::~ChildProcess() {
  close_fd(message_fd_);
  close_fd(stderr_fd_);
  if (pid_ > 0 && !reaped_) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
}

ChildProcess::Pumped ChildProcess::pump(Clock::time_point deadline,
                                        const std::function<void(const std::string&)>& on_message,
                                        const std::function<void(const std::string&)>& on_stderr) {
  if (message_fd_ < 0 && stderr_fd_ < 0) return Pumped::Closed;
  std::array<pollfd, 2> fds{pollfd{message_fd_, POLLIN, 0}, pollfd{stderr_fd_, POLLIN, 0}};
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
  if (left.count() <= 0) return Pumped::TimedOut;
  const int timeout_ms = int(std::min<long long>(left.count(), 60'000));
  const int ready = ::poll(fds.data(), fds.size(), timeout_ms);
  if (ready < 0 && errno != EINTR)
    throw std::runtime_error(std::string("poll: ") + std::strerror(errno));
  if (ready <= 0) return Clock::now() >= deadline ? Pumped::TimedOut : Pumped::Output;
  // stderr first: a crash's last words come before the message pipe's end.
  if (fds[1].revents != 0) read_lines(stderr_fd_, stderr_partial_, on_stderr);
  if (fds[0].revents != 0) read_lines(message_fd_, message_partial_, on_message);
  return message_fd_ < 0 && stderr_fd_ < 0 ? Pumped::Closed : Pumped::Output;
}

void ChildProcess::kill() {
  if (pid_ > 0 && !reaped_) ::kill(pid_, SIGKILL);
}

int ChildProcess::wait() {
  if (reaped_ || pid_ <= 0) return status_;
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0)
    if (errno != EINTR) throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
  reaped_ = true;
  status_ = status;
  return status_;
}

std::string signal_name(int signal) {
  const char* abbrev = ::sigabbrev_np(signal);
  return abbrev != nullptr ? std::string("SIG") + abbrev : "signal " + std::to_string(signal);
}

std::string describe_wait_status(int status) {
  if (WIFEXITED(status)) return "exited with code " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* what = ::sigdescr_np(sig);
    return "killed by signal " + std::to_string(sig) + " (" + signal_name(sig) +
           (what != nullptr ? std::string(": ") + what : std::string()) + ")";
  }
  return "ended with wait status " + std::to_string(status);
}

bool write_fully(int fd, const std::string& text) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += size_t(n);
  }
  return true;
}

}  // namespace sb::run
