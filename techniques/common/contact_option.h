#pragma once
// Contact shadows as an option of any technique: with_contact_option(info)
// returns `info` with four more parameters,
//   contact            (bool, default false) add contact shadows;
//   contact_length, contact_steps, contact_thickness
//                      the march's (common/contact_shadow_pass.h),
// and a `create` that, with contact on, decorates the technique: its own
// render(), then the contact pass in its own timed pass "contact", which
// writes V = min(V_technique, V_contact) into the same target by blending
// (glBlendEquation(GL_MIN)): no extra target, no edit to the technique.
// With contact off the technique is made as before, untouched; the four
// parameters are read either way, so none is ever reported unread
// (config/unread_params.h).
//
// A config asks for it by parameter:
//   {"name": "pcss", "label": "pcss+contact", "params": {"contact": true}}
//
// What the kit guarantees here (shadowbench::shadow_kit, installed):
//   in     a TechniqueInfo whose parameters have none of the four names;
//   out    that TechniqueInfo, its other fields (needs, check, cost weight,
//          temporal) unchanged;
//   GL     none here; the decorated technique's prepare() makes the
//          ContactShadowPass after the technique's own;
//   cost   with contact on, one ContactShadowPass::draw per frame after the
//          technique's render(); off, nothing.
#include "plugin/registry.h"

namespace sb::techniques {

// `info` with the contact option (the rule at the top of this header).
// Throws std::logic_error when `info` already declares one of its names.
// cost: with contact on, one full-screen contact pass per frame.
plugin::TechniqueInfo with_contact_option(plugin::TechniqueInfo info);

}  // namespace sb::techniques
