#pragma once
// Times the named passes of one frame. On software rasterisers (llvmpipe)
// GL_TIME_ELAPSED reports roughly one tile's time, so each pass is bracketed
// by glFinish and a steady CPU clock there; on GPUs timer queries are used.
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "gl/gl.h"

namespace sb::gl {

enum class TimingSource { CpuFinish, GpuQuery };
std::string to_string(TimingSource s);  // "cpu_glfinish" / "gl_timer_query"

class PassTimer {
 public:
  explicit PassTimer(TimingSource source);
  ~PassTimer();
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;

  TimingSource source() const { return source_; }

  void begin_frame();
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
    Scope(PassTimer& t, const std::string& pass) : t_(t) { t_.begin(pass); }
    ~Scope() { t_.end(); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    PassTimer& t_;
  };
  Scope scope(const std::string& pass) { return Scope(*this, pass); }

 private:
  using Clock = std::chrono::steady_clock;
  TimingSource source_;
  Clock::time_point frame_start_;
  Clock::time_point pass_start_;
  std::string current_;
  std::vector<std::pair<std::string, double>> cpu_passes_;
  std::vector<std::pair<std::string, GLuint>> queries_;
  std::vector<GLuint> free_queries_;
};

}  // namespace sb::gl
