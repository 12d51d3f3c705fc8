// A technique that fails on demand, for the isolation tests only (never
// installed): it crashes with SIGSEGV, aborts, hangs, exits, throws, or
// renders slowly, each after saying so on stderr, so a test can check that
// the child's last words reach the failed record. Otherwise it is `none`:
// V = 1 everywhere.
#include <signal.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>

#include "plugin/registry.h"

namespace {

class Fault final : public sb::plugin::Technique {
 public:
  explicit Fault(const sb::core::Params& p)
      : mode_(p.get_string("mode")), at_(p.get_string("at")), slow_ms_(p.get_float("slow_ms")) {}

  void prepare(const sb::plugin::FrameInputs& /*in*/) override {
    if (at_ == "prepare") fail();
  }
  void render(const sb::plugin::FrameInputs& in, sb::gl::PassTimer& timer) override {
    if (at_ == "frame") fail();
    auto pass = timer.scope("clear");
    if (slow_ms_ > 0)
      std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(slow_ms_));
    const std::array<float, 4> one{1.0f, 1.0f, 1.0f, 1.0f};
    glClearNamedFramebufferfv(in.visibility_framebuffer, GL_COLOR, 0, one.data());
  }

 private:
  void fail() const {
    if (mode_ == "none") return;
    std::fprintf(stderr, "fault plugin: about to %s (pid %d)\n", mode_.c_str(), int(::getpid()));
    std::fflush(stderr);
    if (mode_ == "crash") ::raise(SIGSEGV);
    if (mode_ == "abort") std::abort();
    if (mode_ == "exit") ::_exit(3);
    if (mode_ == "throw") throw std::runtime_error("fault plugin: thrown on demand");
    if (mode_ == "hang")
      for (;;) ::pause();
  }
  std::string mode_, at_;
  double slow_ms_;
};

}  // namespace

SHADOWBENCH_PLUGIN_ENTRY(sb::plugin::Registry& registry) {
  registry.add(
      {"fault",
       "fault",
       "test only: crashes, aborts, hangs, exits or throws on demand",
       sb::plugin::Needs{},
       {sb::core::choice_param("mode", "none", {"none", "crash", "abort", "hang", "exit", "throw"},
                               "what to do"),
        sb::core::choice_param("at", "frame", {"prepare", "frame"},
                               "when: in prepare() or in a frame"),
        sb::core::float_param("slow_ms", 0.0, 0.0, 10000.0, "sleep this long in every frame")},
       [](const sb::core::Params& p) { return std::make_unique<Fault>(p); }});
}
