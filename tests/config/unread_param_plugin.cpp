// A technique plugin for the tests of config/unread_params.h: it declares a
// parameter ('forgotten') that its factory never reads. Its cross-parameter
// check reads it, which must not count: only create() does.
#include <array>
#include <memory>

#include "plugin/registry.h"

namespace {

class AllLit final : public sb::plugin::Technique {
 public:
  void prepare(const sb::plugin::FrameInputs& /*in*/) override {}
  void render(const sb::plugin::FrameInputs& in, sb::gl::PassTimer& timer) override {
    auto pass = timer.scope("clear");
    const std::array<float, 4> one{1.0f, 1.0f, 1.0f, 1.0f};
    glClearNamedFramebufferfv(in.visibility_framebuffer, GL_COLOR, 0, one.data());
  }
};

}  // namespace

SHADOWBENCH_PLUGIN_ENTRY(sb::plugin::Registry& registry) {
  sb::plugin::TechniqueInfo info{
      "reads_half",
      "test",
      "reads 'used', never 'forgotten'",
      sb::plugin::Needs{},
      {sb::core::float_param("used", 1.0, 0.0, 2.0, "read by the factory"),
       sb::core::int_param("forgotten", 3, 1, 9, "never read by the factory")},
      [](const sb::core::Params& p) {
        (void)p.get_float("used");
        return std::make_unique<AllLit>();
      }};
  info.check = [](const sb::core::Params& p) -> std::pair<std::string, std::string> {
    if (p.get_int("forgotten") == 7) return {"forgotten", "anything but 7"};
    return {};
  };
  registry.add(std::move(info));
}
