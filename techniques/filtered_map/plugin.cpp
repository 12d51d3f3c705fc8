// The filterable shadow maps: one registration line per variant. Each takes
// the contact-shadow option (common/contact_option.h: "contact": true adds
// screen-space contact shadows).
#include "common/contact_option.h"
#include "filtered_map/filtered_map_variants.h"

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  using sb::techniques::with_contact_option;
  registry.add(with_contact_option(sb::techniques::filtered_map::vsm_info()));
  registry.add(with_contact_option(sb::techniques::filtered_map::esm_info()));
  registry.add(with_contact_option(sb::techniques::filtered_map::evsm_info()));
  registry.add(with_contact_option(sb::techniques::filtered_map::msm_info()));
  registry.add(with_contact_option(sb::techniques::filtered_map::csm_convolution_info()));
}
