// The two-map family (Shypula 2008, ch. 8): one registration line per variant.
#include "plugin/registry.h"

namespace sb::techniques::two_map {
TechniqueInfo two_map_bound_info();
}  // namespace sb::techniques::two_map

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  registry.add(sb::techniques::two_map::two_map_bound_info());
}
