// A technique plugin for tests/e2e/test_failed_jobs.cpp that writes V out
// of range on purpose, at known pixels: its job must fail the visibility
// check, and no table may show a figure for it.
//
// "writes_invalid" clears V to 0.5, then (GL window coordinates, y up) the
// rectangles of kInvalidRects with NaN, +inf, -0.25 and 1.5, and one more
// with 1 + 5e-6, which is within the check's tolerance and so valid.
#include <array>
#include <limits>
#include <memory>

#include "invalid_visibility_rects.h"
#include "plugin/registry.h"

namespace {

using sb::test::kInvalidRects;

class WritesInvalid final : public sb::plugin::Technique {
 public:
  void prepare(const sb::plugin::FrameInputs& /*in*/) override {}
  void render(const sb::plugin::FrameInputs& in, sb::gl::PassTimer& timer) override {
    auto pass = timer.scope("clear");
    const auto clear = [&](float v) {
      const std::array<float, 4> c{v, v, v, v};
      glClearNamedFramebufferfv(in.visibility_framebuffer, GL_COLOR, 0, c.data());
    };
    clear(0.5f);
    glEnable(GL_SCISSOR_TEST);
    for (const auto& r : kInvalidRects) {
      glScissor(r.x, r.y, r.w, r.h);
      clear(r.value);
    }
    glDisable(GL_SCISSOR_TEST);
  }
};

}  // namespace

SHADOWBENCH_PLUGIN_ENTRY(sb::plugin::Registry& registry) {
  registry.add({"writes_invalid",
                "test",
                "writes NaN, inf and V outside [0, 1] at known pixels",
                sb::plugin::Needs{},
                {},
                [](const sb::core::Params& /*p*/) { return std::make_unique<WritesInvalid>(); }});
}
