#include "gl/pass_timer.h"

#include <stdexcept>

namespace sb::gl {

std::string to_string(TimingSource s) {
  return s == TimingSource::CpuFinish ? "cpu_glfinish" : "gl_timer_query";
}

std::string to_string(PassDetail d) { return d == PassDetail::Coarse ? "coarse" : "fine"; }

PassDetail pass_detail_from_string(const std::string& s) {
  if (s == "coarse") return PassDetail::Coarse;
  if (s == "fine") return PassDetail::Fine;
  throw std::invalid_argument("expected coarse or fine, found '" + s + "'");
}

PassTimer::PassTimer(TimingSource source, PassDetail detail) : source_(source), detail_(detail) {}

PassTimer::~PassTimer() {
  for (auto& [name, q] : queries_) free_queries_.push_back(q);
  if (!free_queries_.empty())
    glDeleteQueries(static_cast<GLsizei>(free_queries_.size()), free_queries_.data());
}

void PassTimer::begin_frame() {
  glFinish();
  cpu_passes_.clear();
  open_timed_.clear();
  current_.clear();
  for (auto& [name, q] : queries_) free_queries_.push_back(q);
  queries_.clear();
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
  if (source_ == TimingSource::CpuFinish) {
    glFinish();
    pass_start_ = Clock::now();
  } else {
    GLuint q = 0;
    if (free_queries_.empty()) {
      glGenQueries(1, &q);
    } else {
      q = free_queries_.back();
      free_queries_.pop_back();
    }
    glBeginQuery(GL_TIME_ELAPSED, q);
    queries_.emplace_back(pass, q);
  }
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
    glEndQuery(GL_TIME_ELAPSED);
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
    for (const auto& [name, q] : queries_) {
      GLuint64 ns = 0;
      glGetQueryObjectui64v(q, GL_QUERY_RESULT, &ns);
      add(name, static_cast<double>(ns) * 1e-6);
    }
  }
  return f;
}

}  // namespace sb::gl
