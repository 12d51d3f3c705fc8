#include "gl/pass_timer.h"

#include <algorithm>
#include <stdexcept>

namespace sb::gl {

std::string to_string(TimingSource s) {
  return s == TimingSource::CpuFinish ? "cpu_glfinish" : "gl_timestamp_query";
}

bool timestamp_queries_supported() {
  GLint bits = 0;
  glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &bits);
  return bits > 0;
}

std::string to_string(PassDetail d) { return d == PassDetail::Coarse ? "coarse" : "fine"; }

PassDetail pass_detail_from_string(const std::string& s) {
  if (s == "coarse") return PassDetail::Coarse;
  if (s == "fine") return PassDetail::Fine;
  throw std::invalid_argument("expected coarse or fine, found '" + s + "'");
}

PassTimer::PassTimer(TimingSource source, PassDetail detail) : source_(source), detail_(detail) {
  if (source_ == TimingSource::GpuQuery && !timestamp_queries_supported())
    throw std::runtime_error("GL timestamp queries have 0 bits here: time with CPU clocks");
}

PassTimer::~PassTimer() {
  for (const auto& s : stamped_) free_queries_.push_back(s.end_query);
  if (!free_queries_.empty())
    glDeleteQueries(static_cast<GLsizei>(free_queries_.size()), free_queries_.data());
}

void PassTimer::begin_frame() {
  glFinish();
  cpu_passes_.clear();
  open_timed_.clear();
  current_.clear();
  for (const auto& s : stamped_) free_queries_.push_back(s.end_query);
  stamped_.clear();
  frame_start_ = Clock::now();
}

void PassTimer::begin(const std::string& pass) {
  if (detail_ == PassDetail::Coarse) {
    open_timed_.push_back(false);
    return;
  }
  begin_bracket(pass);
}

void PassTimer::begin_bracket(const std::string& pass) {
  if (!current_.empty())
    throw std::logic_error("pass '" + pass + "' begun inside '" + current_ + "'");
  open_timed_.push_back(true);
  current_ = pass;
  if (source_ == TimingSource::CpuFinish)
    glFinish();
  else
    glGetInteger64v(GL_TIMESTAMP, &gl_start_ns_);  // the GL's clock now, without a sync
  pass_start_ = Clock::now();
}

void PassTimer::end() {
  if (open_timed_.empty()) throw std::logic_error("PassTimer::end without begin");
  close();
}

void PassTimer::close() noexcept {
  if (open_timed_.empty()) return;
  const bool timed = open_timed_.back();
  open_timed_.pop_back();
  if (!timed) return;
  if (source_ == TimingSource::CpuFinish) {
    glFinish();
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - pass_start_).count();
    cpu_passes_.emplace_back(current_, ms);
  } else {
    const double cpu_ms =
        std::chrono::duration<double, std::milli>(Clock::now() - pass_start_).count();
    GLuint q = 0;
    if (free_queries_.empty()) {
      glGenQueries(1, &q);
    } else {
      q = free_queries_.back();
      free_queries_.pop_back();
    }
    glQueryCounter(q, GL_TIMESTAMP);
    // The bracket's commands start now, as after CpuFinish's glFinish, not
    // whenever the driver would flush them: the wait would count as theirs.
    glFlush();
    stamped_.push_back({current_, gl_start_ns_, q, cpu_ms});
  }
  current_.clear();
}

PassTimer::Frame PassTimer::end_frame() {
  glFinish();
  Frame f;
  f.total_ms = std::chrono::duration<double, std::milli>(Clock::now() - frame_start_).count();
  auto add = [&f](const std::string& name, double ms) {
    for (auto& [n, v] : f.passes)
      if (n == name) {
        v += ms;
        return;
      }
    f.passes.emplace_back(name, ms);
  };
  if (source_ == TimingSource::CpuFinish) {
    for (const auto& [name, ms] : cpu_passes_) add(name, ms);
  } else {
    // Brackets run in sequence: one starts when the CPU enters it or when
    // the GPU has finished the previous one's commands, whichever is later,
    // so that no GPU work counts in two brackets. Never less than the CPU's
    // time inside it: its CPU work may have overlapped the previous
    // bracket's GPU work, which llvmpipe's brackets would have serialised.
    GLint64 previous_end_ns = 0;
    for (const auto& s : stamped_) {
      GLuint64 end = 0;
      glGetQueryObjectui64v(s.end_query, GL_QUERY_RESULT, &end);
      const auto end_ns = static_cast<GLint64>(end);
      const GLint64 start_ns = std::max(s.gl_start_ns, previous_end_ns);
      const double gl_ms = static_cast<double>(end_ns - start_ns) * 1e-6;
      // A bracket lies inside its frame: outside it, the GL's two clocks
      // (glGetInteger64v and the query) disagree, and no time can be trusted.
      constexpr double kClockSlackMs = 1.0;
      if (gl_ms < -kClockSlackMs || gl_ms > f.total_ms + kClockSlackMs)
        throw std::runtime_error("GL timestamps put bracket '" + s.name + "' at " +
                                 std::to_string(gl_ms) + " ms in a frame of " +
                                 std::to_string(f.total_ms) + " ms: the GL's clocks disagree");
      add(s.name, std::max(gl_ms, s.cpu_ms));
      previous_end_ns = std::max(previous_end_ns, end_ns);
    }
  }
  return f;
}

}  // namespace sb::gl
