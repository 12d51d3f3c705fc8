// The shadow-map family: one registration line per variant.
#include "shadow_map/shadow_map_variants.h"

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  registry.add(sb::shadow::hard_shadow_map_info());
  registry.add(sb::shadow::pcf_box_info());
}
