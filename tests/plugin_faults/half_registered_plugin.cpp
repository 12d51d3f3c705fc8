// A plugin that registers one technique, then one a shipped plugin already
// registered (pcf_box): the registry must refuse the whole module, the
// first technique too. For the load-failure tests only.
#include <memory>

#include "plugin/registry.h"

namespace {

class Never final : public sb::plugin::Technique {
 public:
  void prepare(const sb::plugin::FrameInputs& /*in*/) override {}
  void render(const sb::plugin::FrameInputs& /*in*/, sb::gl::PassTimer& /*timer*/) override {}
};

}  // namespace

SHADOWBENCH_PLUGIN_ENTRY(sb::plugin::Registry& registry) {
  const auto make = [](const sb::core::Params&) { return std::make_unique<Never>(); };
  registry.add({"half_registered",
                "half_registered",
                "registered before the clash",
                sb::plugin::Needs{},
                {},
                make});
  registry.add({"pcf_box",
                "half_registered",
                "clashes with the shipped pcf_box",
                sb::plugin::Needs{},
                {},
                make});
}
