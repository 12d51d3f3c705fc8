// A technique plugin for the tests of config/unread_params.h: it declares a
// parameter ('forgotten') that its factory never reads. Its cross-parameter
// check reads it, which must not count: only create() does.
#include <array>
#include <memory>

#include "plugin/registry.h"

namespace {

class AllLit final : public sb::Technique {
 public:
  void prepare(const sb::FrameInputs& /*in*/) override {}
  void render(const sb::FrameInputs& in, sb::gl::PassTimer& timer) override {
    auto pass = timer.scope("clear");
    const std::array<float, 4> one{1.0f, 1.0f, 1.0f, 1.0f};
    glClearNamedFramebufferfv(in.visibility_framebuffer, GL_COLOR, 0, one.data());
  }
};

}  // namespace

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  sb::TechniqueInfo info{"reads_half",
                         "test",
                         "reads 'used', never 'forgotten'",
                         sb::Needs{},
                         {sb::float_param("used", 1.0, 0.0, 2.0, "read by the factory"),
                          sb::int_param("forgotten", 3, 1, 9, "never read by the factory")},
                         [](const sb::Params& p) {
                           (void)p.get_float("used");
                           return std::make_unique<AllLit>();
                         }};
  info.check = [](const sb::Params& p) -> std::pair<std::string, std::string> {
    if (p.get_int("forgotten") == 7) return {"forgotten", "anything but 7"};
    return {};
  };
  registry.add(std::move(info));
}
