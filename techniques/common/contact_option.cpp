#include "common/contact_option.h"

#include <memory>
#include <stdexcept>
#include <utility>

#include "common/contact_shadow_pass.h"

namespace sb::techniques {

using core::Params;
using plugin::FrameInputs;
using plugin::Technique;

namespace {

constexpr const char* kPrefix = "contact_";

// The technique, then V = min(V, V_contact) in its own pass.
class WithContactShadows final : public Technique {
 public:
  WithContactShadows(std::unique_ptr<Technique> inner, ContactShadowSettings settings)
      : inner_(std::move(inner)), settings_(settings) {}
  void prepare(const FrameInputs& in) override {
    inner_->prepare(in);
    pass_ = ContactShadowPass(settings_);
  }
  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    inner_->render(in, timer);
    auto pass = timer.scope("contact");
    pass_.draw(in, ContactCombine::Min);
  }

 private:
  std::unique_ptr<Technique> inner_;
  ContactShadowSettings settings_;
  ContactShadowPass pass_;
};

}  // namespace

plugin::TechniqueInfo with_contact_option(plugin::TechniqueInfo info) {
  std::vector<core::ParamSpec> added = {core::bool_param(
      "contact", false,
      "add screen-space contact shadows: V = min(V, V_contact), timed as pass \"contact\"")};
  for (auto& p : contact_shadow_params(kPrefix)) {
    p.enabled_by = "contact";  // off, they change nothing: no sensitivity to them
    added.push_back(std::move(p));
  }
  for (const auto& p : added)
    for (const auto& own : info.params)
      if (own.name == p.name)
        throw std::logic_error(info.name + " already declares '" + p.name +
                               "': it cannot take the contact option");
  for (auto& p : added) info.params.push_back(std::move(p));
  info.create = [create = std::move(info.create)](const Params& p) -> std::unique_ptr<Technique> {
    // Read whether contact is on or not: none of them is ever unread.
    const bool contact = p.get_bool("contact");
    const ContactShadowSettings settings = contact_shadow_settings(p, kPrefix);
    std::unique_ptr<Technique> inner = create(p);
    if (!contact) return inner;
    return std::make_unique<WithContactShadows>(std::move(inner), settings);
  };
  return info;
}

}  // namespace sb::techniques
