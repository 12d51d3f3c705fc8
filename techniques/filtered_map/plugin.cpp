// The filterable shadow maps: one registration line per variant.
#include "filtered_map/filtered_map_variants.h"

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  registry.add(sb::techniques::filtered_map::vsm_info());
  registry.add(sb::techniques::filtered_map::esm_info());
  registry.add(sb::techniques::filtered_map::evsm_info());
  registry.add(sb::techniques::filtered_map::msm_info());
  registry.add(sb::techniques::filtered_map::csm_convolution_info());
}
