// The cascaded family: shadow maps for the sun, split along the camera's
// view. Each takes the contact-shadow option (common/contact_option.h:
// "contact": true adds screen-space contact shadows along to_sun()).
#include "cascaded/cascaded_variants.h"
#include "common/contact_option.h"

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  using sb::techniques::with_contact_option;
  registry.add(with_contact_option(sb::techniques::cascaded::cascaded_shadow_map_info()));
  registry.add(with_contact_option(sb::techniques::cascaded::sdsm_info()));
  registry.add(with_contact_option(sb::techniques::cascaded::virtual_shadow_map_info()));
}
