// A plugin "my_pcf" that calls a function nothing defines. Linked as plain
// `g++ -shared` does (no --no-undefined), it links, and fails only when the
// driver dlopens it: "undefined symbol: ...". For the load-failure tests only.
#include <memory>

#include "plugin/registry.h"

int sb_test_function_nobody_defines();  // declared, never defined

namespace {

class Never final : public sb::plugin::Technique {
 public:
  void prepare(const sb::plugin::FrameInputs& /*in*/) override {}
  void render(const sb::plugin::FrameInputs& /*in*/, sb::gl::PassTimer& /*timer*/) override {}
};

}  // namespace

SHADOWBENCH_PLUGIN_ENTRY(sb::plugin::Registry& registry) {
  if (sb_test_function_nobody_defines() == 0) return;
  registry.add(
      {"my_pcf", "my_pcf", "never loads", sb::plugin::Needs{}, {}, [](const sb::core::Params&) {
         return std::make_unique<Never>();
       }});
}
