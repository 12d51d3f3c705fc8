// The shadow-map family of compared depth maps: one registration line per variant.
#include "shadow_map/shadow_map_variants.h"

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  registry.add(sb::shadow::hard_shadow_map_info());
  registry.add(sb::shadow::pcf_box_info());
  registry.add(sb::shadow::pcf_gauss_info());
  registry.add(sb::shadow::pcf_jitter_info());
  registry.add(sb::shadow::pcss_info());
  registry.add(sb::shadow::blurred_visibility_info());
  registry.add(sb::shadow::psm_info());
  registry.add(sb::shadow::lispsm_info());
  registry.add(sb::shadow::extended_light_maps_info());
  registry.add(sb::shadow::heidrich_linear_info());
}
