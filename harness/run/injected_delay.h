#pragma once
// A known slowdown on purpose: SHADOWBENCH_INJECT_DELAY="<technique variant>@<ms>"
// makes every frame of that technique variant busy-wait <ms> milliseconds
// inside its timing bracket. It exists to measure the CI gate: how often
// `compare` catches a slowdown of a known size (bench/ci_gate, docs/ci.md).
// Every record it touches carries a warning that says so.
#include <optional>
#include <string>

namespace sb {

inline constexpr const char* kInjectDelayVariable = "SHADOWBENCH_INJECT_DELAY";

class InjectedDelay {
 public:
  // nullopt when the variable is unset or empty; InputError naming the
  // variable when it is malformed.
  static std::optional<InjectedDelay> from_environment();
  static InjectedDelay parse(const std::string& value);

  bool applies_to(const std::string& technique_variant) const {
    return technique_variant == variant_;
  }
  double milliseconds() const { return ms_; }
  // Spins on the steady clock: a fixed wall time, whatever the scheduler.
  void wait() const;
  std::string describe() const;  // the records' warning

 private:
  InjectedDelay(std::string variant, double ms) : variant_(std::move(variant)), ms_(ms) {}
  std::string variant_;
  double ms_ = 0;
};

}  // namespace sb
