// The filterable shadow maps: one registration line per variant.
#include "filtered_map/filtered_map_variants.h"

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  registry.add(sb::shadow::vsm_info());
  registry.add(sb::shadow::esm_info());
  registry.add(sb::shadow::evsm_info());
  registry.add(sb::shadow::msm_info());
  registry.add(sb::shadow::csm_convolution_info());
}
