#include "run/injected_delay.h"

#include <chrono>
#include <cmath>
#include <cstdlib>

#include "core/error.h"

namespace sb::run {

using core::InputError;

std::optional<InjectedDelay> InjectedDelay::from_environment() {
  const char* value = std::getenv(kInjectDelayVariable);
  if (value == nullptr || *value == '\0') return std::nullopt;
  return parse(value);
}

InjectedDelay InjectedDelay::parse(const std::string& value) {
  const auto fail = [&](const std::string& what) -> InjectedDelay {
    throw InputError("", kInjectDelayVariable,
                     what +
                         " (expected <technique variant>@<milliseconds> or "
                         "<technique variant>@<percent>%, e.g. \"pcf_box/k=3,size=1024@1.5\" "
                         "or \"pcf_box/k=3,size=1024@20%\"), found \"" +
                         value + "\"");
  };
  const size_t at = value.rfind('@');
  if (at == std::string::npos || at == 0) return fail("no technique variant before '@'");
  std::string amount_text = value.substr(at + 1);
  const bool relative = !amount_text.empty() && amount_text.back() == '%';
  if (relative) amount_text.pop_back();
  char* end = nullptr;
  const double amount = std::strtod(amount_text.c_str(), &end);
  const double limit = relative ? 1000 : 10000;
  if (amount_text.empty() || end != amount_text.c_str() + amount_text.size() ||
      !std::isfinite(amount) || amount <= 0 || amount > limit)
    return fail(relative ? "the share must be a percentage in (0, 1000]"
                         : "the delay must be a number of milliseconds in (0, 10000]");
  return {value.substr(0, at), relative ? amount / 100 : amount, relative};
}

void InjectedDelay::wait(double frame_ms) const {
  const auto until = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double, std::milli>(milliseconds(frame_ms)));
  while (std::chrono::steady_clock::now() < until) {
  }
}

std::string InjectedDelay::describe() const {
  const std::string amount = relative_ ? std::to_string(100 * amount_) + " % of the frame's time"
                                       : std::to_string(amount_) + " ms";
  return "every frame of this job ends with an injected busy-wait of " + amount + " (" +
         kInjectDelayVariable + "): a test of the CI gate, not a measurement";
}

}  // namespace sb::run
