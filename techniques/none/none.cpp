// none — no shadows: V = 1 everywhere. The floor of every time chart and the
// ceiling of every error chart.
#include <array>
#include <memory>

#include "plugin/registry.h"

namespace sb::techniques::none {
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
}  // namespace sb::techniques::none

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  using namespace sb;
  using namespace sb::techniques::none;
  registry.add({.name = "none",
                .family = "none",
                .summary = "no shadows: visibility 1 everywhere",
                .needs = Needs{need::kSunOrLocalLight},
                .params = {},
                .create = [](const Params&) { return std::make_unique<NoShadows>(); }});
}
