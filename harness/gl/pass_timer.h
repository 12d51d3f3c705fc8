#pragma once
// Times one frame in brackets. On software rasterisers (llvmpipe)
// GL_TIME_ELAPSED reports roughly one tile's time, so each bracket is closed
// by glFinish and a steady CPU clock there; on GPUs timer queries are used.
//
// Two kinds of bracket: the harness's own (`bracket`: the G-buffer, the whole
// technique, shading), always timed; and a technique's named passes
// (`scope`), timed only in PassDetail::Fine. Every bracket costs a sync, so
// coarse timing gives every technique the same three, whatever its number
// of passes (accumulation has 2N + 1).
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "gl/gl.h"

namespace sb::gl {

enum class TimingSource { CpuFinish, GpuQuery };
std::string to_string(TimingSource s);  // "cpu_glfinish" / "gl_timer_query"

enum class PassDetail { Coarse, Fine };
std::string to_string(PassDetail d);                       // "coarse" / "fine"
PassDetail pass_detail_from_string(const std::string& s);  // throws std::invalid_argument

class PassTimer {
 public:
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
  Frame end_frame();

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
  std::vector<std::pair<std::string, GLuint>> queries_;
  std::vector<GLuint> free_queries_;
};

}  // namespace sb::gl
