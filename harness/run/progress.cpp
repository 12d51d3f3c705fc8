#include "run/progress.h"

#include <cmath>

namespace sb::run {

Progress::Progress(std::FILE* out, bool enabled, size_t total)
    : out_(out), enabled_(enabled && out != nullptr), total_(total) {}

double Progress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
}

void Progress::start_job(const std::string& scene, const std::string& resolution,
                         const std::string& technique) {
  current_ = scene + " @ " + resolution + "  " + technique;
  draw();
}

void Progress::finish_job() {
  ++done_;
  ++ran_;
  current_.clear();
}

std::optional<double> Progress::eta_seconds(size_t ran, size_t remaining, double elapsed_seconds) {
  if (ran == 0) return std::nullopt;
  return elapsed_seconds / double(ran) * double(remaining);
}

std::string Progress::format_duration(double seconds) {
  const long s = std::lround(std::max(seconds, 0.0));
  char buf[32];
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%lds", s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, (s % 3600) / 60);
  return buf;
}

std::string Progress::line(double elapsed_seconds) const {
  std::string text =
      "[" + std::to_string(std::min(done_ + 1, total_)) + "/" + std::to_string(total_) + "]";
  if (!current_.empty()) text += " " + current_;
  const auto eta = eta_seconds(ran_, total_ - std::min(done_, total_), elapsed_seconds);
  text += eta ? "  ETA " + format_duration(*eta) : std::string("  ETA --");
  return text;
}

void Progress::clear() {
  if (!enabled_ || !drawn_) return;
  std::fputs("\r\033[2K", out_);  // carriage return, erase the line
  std::fflush(out_);
  drawn_ = false;
}

void Progress::draw() {
  if (!enabled_ || current_.empty()) return;
  std::fputs("\r\033[2K", out_);
  std::fputs(line(elapsed()).c_str(), out_);
  std::fflush(out_);
  drawn_ = true;
}

}  // namespace sb::run
