// contact_shadows — screen-space contact shadows alone, V = V_contact: the
// short march towards the light through the G-buffer that engines add on
// top of their shadow maps (common/contact_shadow_pass.h: the rule, its
// sources and its limits), run by itself so that its own error shows. The
// map techniques take it as an option ("contact": true,
// common/contact_option.h).
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <memory>

#include "common/contact_shadow_pass.h"
#include "plugin/registry.h"

namespace sb::techniques::contact {
namespace {

class ContactShadows final : public Technique {
 public:
  explicit ContactShadows(const Params& p) : settings_(contact_shadow_settings(p, "")) {}
  void prepare(const FrameInputs& /*in*/) override { pass_ = ContactShadowPass(settings_); }
  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    auto pass = timer.scope("contact");
    pass_.draw(in, ContactCombine::Replace);
  }

 private:
  ContactShadowSettings settings_;
  ContactShadowPass pass_;
};

}  // namespace
}  // namespace sb::techniques::contact

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  using namespace sb;
  registry.add({.name = "contact_shadows",
                .family = "contact",
                .summary =
                    "screen-space contact shadows alone: a short march towards the light "
                    "through the G-buffer's depths (Sousa et al. at Crytek, Unreal Engine, Bend "
                    "Studio 2023); an option of the map techniques (contact: true)",
                .needs = Needs{need::kSunOrLocalLight},
                .params = techniques::contact_shadow_params(""),
                .create = [](const Params& p) {
                  return std::make_unique<techniques::contact::ContactShadows>(p);
                }});
}
