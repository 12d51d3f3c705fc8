// none — no shadows: V = 1 everywhere. The floor of every time chart and the
// ceiling of every error chart.
#include <array>
#include <memory>

#include "plugin/registry.h"

namespace sb {
namespace {

class NoShadows final : public Technique {
 public:
  void prepare(const FrameInputs& /*in*/) override {}
  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    auto pass = timer.scope("clear");
    const std::array<float, 4> one{1.0f, 1.0f, 1.0f, 1.0f};
    glClearNamedFramebufferfv(in.visibility_framebuffer, GL_COLOR, 0, one.data());
  }
};

}  // namespace
}  // namespace sb

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  registry.add({.name = "none",
                .family = "none",
                .summary = "no shadows: visibility 1 everywhere",
                .needs = sb::Needs{},
                .params = {},
                .create = [](const sb::Params&) { return std::make_unique<sb::NoShadows>(); }});
}
