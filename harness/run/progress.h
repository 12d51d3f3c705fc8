#pragma once
// A one-line progress display for long runs: job i/N, the scene, resolution
// and technique being run, and an ETA. It draws only on a terminal (and not
// with --quiet); log lines printed meanwhile go through clear()/draw() so
// the two do not interleave.
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>

namespace sb::run {

class Progress {
 public:
  Progress(std::FILE* out, bool enabled, size_t total);
  // Jobs done without running (resumed from an earlier run, skipped, or
  // failed before they started): counted, but not part of the ETA's rate.
  void add_done_without_running(size_t n) { done_ += n; }
  void start_job(const std::string& scene, const std::string& resolution,
                 const std::string& technique);
  void finish_job();
  void clear();  // erases the line (call before printing anything else)
  void draw();   // (re)draws it
  // The text drawn, e.g. "[12/57] jeep @ 800x600  pcss  ETA 3m05s".
  std::string line(double elapsed_seconds) const;

  // Seconds left, from the mean time of the jobs run so far in this process;
  // nothing before the first job finished.
  static std::optional<double> eta_seconds(size_t ran, size_t remaining, double elapsed_seconds);
  static std::string format_duration(double seconds);  // "42s", "3m05s", "1h02m"

 private:
  double elapsed() const;
  std::FILE* out_;
  bool enabled_;
  size_t total_;
  size_t done_ = 0;
  size_t ran_ = 0;  // finished by this process
  std::string current_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
};

}  // namespace sb::run
