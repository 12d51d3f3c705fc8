// The shadow-map family of compared depth maps: one registration line per
// variant. The single-map lookups take the contact-shadow option
// (common/contact_option.h: "contact": true adds screen-space contact shadows).
#include "common/contact_option.h"
#include "shadow_map/shadow_map_variants.h"

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  using sb::techniques::with_contact_option;
  registry.add(with_contact_option(sb::techniques::shadow_map::hard_shadow_map_info()));
  registry.add(with_contact_option(sb::techniques::shadow_map::pcf_box_info()));
  registry.add(with_contact_option(sb::techniques::shadow_map::pcf_gauss_info()));
  registry.add(with_contact_option(sb::techniques::shadow_map::pcf_jitter_info()));
  registry.add(with_contact_option(sb::techniques::shadow_map::pcss_info()));
  registry.add(sb::techniques::shadow_map::blurred_visibility_info());
  registry.add(sb::techniques::shadow_map::psm_info());
  registry.add(sb::techniques::shadow_map::lispsm_info());
  registry.add(sb::techniques::shadow_map::extended_light_maps_info());
  registry.add(sb::techniques::shadow_map::heidrich_linear_info());
}
