#pragma once
// Test-only: when each process of a run wrote and when it timed frames, on
// one clock, so that a test can check that no write of the parent's
// overlaps a timed frame (docs/robustness.md, "The parent's writes and the
// timed frames"). Off unless the environment asks:
//   SHADOWBENCH_IO_TRACE=<file>       every process of the run (and of both
//                                     builds under compare-builds) appends
//                                     one line per span to <file>: "<pid>
//                                     <parent pid> <kind> <begin_ns> <end_ns>
//                                     <what>"
//                                     on CLOCK_MONOTONIC, which all share.
//                                     Kinds: "timed" (one timed frame and its
//                                     control frame), "parent-io" (the
//                                     parent storing a record, printing a
//                                     line, writing the reports), "await"
//                                     (a child waiting for the parent's
//                                     answer before a job's frames).
//   SHADOWBENCH_SLOW_PARENT_IO=<ms>   with the trace on, storing a record
//                                     takes at least <ms>: a slow disk on
//                                     purpose, so that a write that can
//                                     overlap a frame does.
#include <cstdint>
#include <string>
#include <vector>

namespace sb::run {

inline constexpr const char* kIoTraceVariable = "SHADOWBENCH_IO_TRACE";
inline constexpr const char* kSlowParentIoVariable = "SHADOWBENCH_SLOW_PARENT_IO";

struct TraceSpan {
  std::string kind, what;
  std::int64_t begin_ns = 0, end_ns = 0;
};

// CLOCK_MONOTONIC in nanoseconds: one clock for every process.
std::int64_t monotonic_ns();
bool io_trace_enabled();
// SHADOWBENCH_SLOW_PARENT_IO in nanoseconds (0 when unset or tracing is off);
// InputError naming the variable when it is malformed.
std::int64_t slow_parent_io_ns();
// Appends the spans to the trace file in one write; nothing when tracing is
// off.
void write_trace(const std::vector<TraceSpan>& spans);

// One span of the parent's I/O, from construction to destruction, written
// to the trace at its end. A span that stores a record (`slow_disk`) lasts
// at least SHADOWBENCH_SLOW_PARENT_IO milliseconds. Costs one getenv when
// tracing is off.
class ParentIoSpan {
 public:
  explicit ParentIoSpan(std::string what, bool slow_disk = false);
  ~ParentIoSpan();
  ParentIoSpan(const ParentIoSpan&) = delete;
  ParentIoSpan& operator=(const ParentIoSpan&) = delete;

 private:
  std::string what_;
  std::int64_t begin_ns_ = 0, slow_ns_ = 0;
};

}  // namespace sb::run
