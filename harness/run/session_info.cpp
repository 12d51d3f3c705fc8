#include "run/session_info.h"

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>

#include "run/job_identity.h"

namespace sb::run {

using record::SessionRecord;

namespace {

std::string random_hex64() {
  std::random_device device;
  const std::uint64_t value = (std::uint64_t(device()) << 32) ^ std::uint64_t(device());
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(value));
  return buf;
}

std::string host_name() {
  char buf[256] = {};
  if (gethostname(buf, sizeof buf - 1) != 0) return "";
  return buf;
}

}  // namespace

std::optional<double> loadavg_one_minute(std::string_view loadavg) {
  const std::string text(loadavg.substr(0, loadavg.find(' ')));
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || (*end != '\0' && *end != '\n') || !std::isfinite(v) || v < 0)
    return std::nullopt;
  return v;
}

SessionRecord start_session() {
  SessionRecord s;
  s.id = random_hex64();
  s.started = now_iso8601();
  s.host = host_name();
  std::ifstream in("/proc/loadavg");
  std::ostringstream text;
  text << in.rdbuf();
  s.load_average = loadavg_one_minute(text.str()).value_or(0.0);
  return s;
}

}  // namespace sb::run
