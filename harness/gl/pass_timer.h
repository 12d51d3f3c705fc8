#pragma once
// Times one frame in brackets. A bracket's time is the wall time from its
// start to the end of its last command, CPU work included, on either kind:
// - CpuFinish (llvmpipe and other software rasterisers, whose
//   GL_TIME_ELAPSED reports roughly one tile's time): glFinish and a steady
//   clock at both ends.
// - GpuQuery (GPUs): GL timestamps, without a sync. The start is the GL's
//   time when the CPU enters the bracket (glGetInteger64v(GL_TIMESTAMP)), or
//   the GPU's end of the previous bracket's commands if that is later; the
//   end is a timestamp query after the bracket's last command. A GPU's
//   GL_TIME_ELAPSED would count only what the GPU executes, so a technique's
//   CPU work (silhouettes, read-backs, CPU reconstruction) would go missing.
//   The time is never less than the CPU's own time inside the bracket.
//
// Two kinds of bracket: the harness's own (`bracket`: the G-buffer, the whole
// technique, shading), always timed; and a technique's named passes
// (`scope`), timed only in PassDetail::Fine. Every CpuFinish bracket costs a
// sync, so coarse timing gives every technique the same three, whatever its
// number of passes (accumulation has 2N + 1).
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "gl/gl.h"

namespace sb::gl {

enum class TimingSource { CpuFinish, GpuQuery };
// "cpu_glfinish" / "gl_timestamp_query" (records before December 2026 have
// "gl_timer_query": GL_TIME_ELAPSED brackets, without the CPU's work).
std::string to_string(TimingSource s);
// Whether the current context's timestamp queries count (GL_QUERY_COUNTER_BITS
// of GL_TIMESTAMP is not 0): GpuQuery needs them.
bool timestamp_queries_supported();

enum class PassDetail { Coarse, Fine };
std::string to_string(PassDetail d);                       // "coarse" / "fine"
PassDetail pass_detail_from_string(const std::string& s);  // throws std::invalid_argument

class PassTimer {
 public:
  // With GpuQuery, throws std::runtime_error when the context has no
  // timestamp queries: its times would be silently wrong.
  explicit PassTimer(TimingSource source, PassDetail detail = PassDetail::Fine);
  ~PassTimer();
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;

  TimingSource source() const { return source_; }
  PassDetail detail() const { return detail_; }
  void set_detail(PassDetail detail) { detail_ = detail; }

  void begin_frame();
  // A harness bracket, timed in either detail.
  void begin_bracket(const std::string& name);
  // A technique's pass: a bracket in Fine detail, nothing in Coarse.
  void begin(const std::string& pass);
  void end();
  // Milliseconds per pass for this frame (passes in first-use order; a pass
  // begun twice is summed) and the whole frame's wall time.
  struct Frame {
    std::vector<std::pair<std::string, double>> passes;
    double total_ms = 0.0;
  };
  Frame end_frame();  // GpuQuery: throws std::runtime_error if the GL's clocks disagree

  // RAII pass bracket: `auto p = timer.scope("depth");`
  class Scope {
   public:
    Scope(PassTimer& t, const std::string& pass, bool harness) : t_(t) {
      if (harness)
        t_.begin_bracket(pass);
      else
        t_.begin(pass);
    }
    ~Scope() { t_.close(); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    PassTimer& t_;
  };
  Scope scope(const std::string& pass) { return Scope(*this, pass, false); }
  Scope bracket(const std::string& name) { return Scope(*this, name, true); }

 private:
  // end() without its checks: a Scope always has a bracket to close.
  void close() noexcept;

 private:
  using Clock = std::chrono::steady_clock;
  TimingSource source_;
  PassDetail detail_;
  // Nesting: a technique's passes inside the harness's "technique" bracket
  // are not timed (Coarse), so end() must know which begin it closes.
  std::vector<bool> open_timed_;
  Clock::time_point frame_start_;
  Clock::time_point pass_start_;
  std::string current_;
  std::vector<std::pair<std::string, double>> cpu_passes_;
  // GpuQuery: each closed bracket's start on the GL's clock, its end query
  // and the CPU's time inside it, in the order they were closed.
  struct Stamped {
    std::string name;
    GLint64 gl_start_ns = 0;
    GLuint end_query = 0;
    double cpu_ms = 0.0;
  };
  GLint64 gl_start_ns_ = 0;
  std::vector<Stamped> stamped_;
  std::vector<GLuint> free_queries_;
};

}  // namespace sb::gl
