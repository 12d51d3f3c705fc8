// The outer-penumbra family (a hard map plus silhouette bands): one
// registration line per variant.
#include "penumbra_map/outer_penumbra_variants.h"

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  registry.add(sb::techniques::penumbra_map::penumbra_maps_info());
  registry.add(sb::techniques::penumbra_map::smoothies_info());
}
