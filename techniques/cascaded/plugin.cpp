// The cascaded family: shadow maps for the sun, split along the camera's view.
#include "cascaded/cascaded_variants.h"

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  registry.add(sb::techniques::cascaded::cascaded_shadow_map_info());
  registry.add(sb::techniques::cascaded::sdsm_info());
  registry.add(sb::techniques::cascaded::virtual_shadow_map_info());
}
