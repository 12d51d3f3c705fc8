#include "run/io_trace.h"

#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <ctime>

#include "core/error.h"
#include "run/child_process.h"

namespace sb::run {

using core::InputError;

namespace {

const char* trace_file() {
  const char* file = std::getenv(kIoTraceVariable);
  return file != nullptr && *file != '\0' ? file : nullptr;
}

}  // namespace

std::int64_t slow_parent_io_ns() {
  const char* value = std::getenv(kSlowParentIoVariable);
  if (value == nullptr || *value == '\0' || trace_file() == nullptr) return 0;
  char* end = nullptr;
  const double ms = std::strtod(value, &end);
  if (*end != '\0' || !std::isfinite(ms) || ms <= 0 || ms > 10000)
    throw InputError(
        "", kSlowParentIoVariable,
        "expected a number of milliseconds in (0, 10000], found \"" + std::string(value) + "\"");
  return std::int64_t(ms * 1e6);
}

std::int64_t monotonic_ns() {
  timespec t{};
  ::clock_gettime(CLOCK_MONOTONIC, &t);
  return std::int64_t(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

bool io_trace_enabled() { return trace_file() != nullptr; }

void write_trace(const std::vector<TraceSpan>& spans) {
  const char* file = trace_file();
  if (file == nullptr || spans.empty()) return;
  std::string text;
  for (const TraceSpan& s : spans)
    text += std::to_string(::getpid()) + " " + std::to_string(::getppid()) + " " + s.kind + " " +
            std::to_string(s.begin_ns) + " " + std::to_string(s.end_ns) + " " + s.what + "\n";
  // O_APPEND: every process's lines land whole, whoever writes at once.
  const int fd = ::open(file, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return;
  write_fully(fd, text);
  ::close(fd);
}

ParentIoSpan::ParentIoSpan(std::string what, bool slow_disk) : what_(std::move(what)) {
  if (!io_trace_enabled()) return;
  begin_ns_ = monotonic_ns();
  if (slow_disk) slow_ns_ = slow_parent_io_ns();
}

ParentIoSpan::~ParentIoSpan() {
  if (!io_trace_enabled()) return;
  // The slow disk: asleep, as a process blocked on a write is.
  for (const std::int64_t until = begin_ns_ + slow_ns_; monotonic_ns() < until;) {
    const timespec pause{0, 1'000'000};
    ::nanosleep(&pause, nullptr);
  }
  write_trace({{"parent-io", what_, begin_ns_, monotonic_ns()}});
}

}  // namespace sb::run
