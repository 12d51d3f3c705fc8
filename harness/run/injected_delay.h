#pragma once
// A known slowdown on purpose: SHADOWBENCH_INJECT_DELAY makes every frame of
// one technique variant busy-wait at its end, in a bracket of its own
// ("injected delay", counted in the frame and the technique's time):
//   "<technique variant>@<ms>"   a fixed number of milliseconds;
//   "<technique variant>@<p>%"   p % of that very frame's time so far, so
//                                the frame is p % slower however loaded the
//                                machine is.
// It exists to measure the CI gate: how often `compare` catches a slowdown
// of a known size (bench/ci_gate_trials.py, docs/ci.md). Every record it
// touches carries a warning that says so.
#include <optional>
#include <string>

namespace sb::run {

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
  // How long to wait after a frame that took `frame_ms` so far.
  double milliseconds(double frame_ms) const { return relative_ ? amount_ * frame_ms : amount_; }
  // Spins on the steady clock for milliseconds(frame_ms): wall time,
  // whatever the scheduler does meanwhile.
  void wait(double frame_ms) const;
  std::string describe() const;  // the records' warning

 private:
  InjectedDelay(std::string variant, double amount, bool relative)
      : variant_(std::move(variant)), amount_(amount), relative_(relative) {}
  std::string variant_;
  double amount_ = 0;  // milliseconds, or a fraction of the frame when relative
  bool relative_ = false;
};

}  // namespace sb::run
