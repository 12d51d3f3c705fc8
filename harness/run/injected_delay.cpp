#include "run/injected_delay.h"

#include <chrono>
#include <cmath>
#include <cstdlib>

#include "core/error.h"

namespace sb {

std::optional<InjectedDelay> InjectedDelay::from_environment() {
  const char* value = std::getenv(kInjectDelayVariable);
  if (value == nullptr || *value == '\0') return std::nullopt;
  return parse(value);
}

InjectedDelay InjectedDelay::parse(const std::string& value) {
  const auto fail = [&](const std::string& what) -> InjectedDelay {
    throw InputError("", kInjectDelayVariable,
                     what +
                         " (expected <technique variant>@<milliseconds>, e.g. "
                         "\"pcf_box/k=3,size=1024@1.5\"), found \"" +
                         value + "\"");
  };
  const size_t at = value.rfind('@');
  if (at == std::string::npos || at == 0) return fail("no technique variant before '@'");
  const std::string ms_text = value.substr(at + 1);
  char* end = nullptr;
  const double ms = std::strtod(ms_text.c_str(), &end);
  if (ms_text.empty() || end != ms_text.c_str() + ms_text.size() || !std::isfinite(ms) || ms <= 0 ||
      ms > 10000)
    return fail("the delay must be a number of milliseconds in (0, 10000]");
  return {value.substr(0, at), ms};
}

void InjectedDelay::wait() const {
  const auto until = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double, std::milli>(ms_));
  while (std::chrono::steady_clock::now() < until) {
  }
}

std::string InjectedDelay::describe() const {
  return "every timed frame includes an injected busy-wait of " + std::to_string(ms_) + " ms (" +
         kInjectDelayVariable + "): a test of the CI gate, not a measurement";
}

}  // namespace sb
