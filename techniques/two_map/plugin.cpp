// The two-map family (Shypula 2008, ch. 8): one registration line per variant.
#include "plugin/registry.h"

namespace sb::shadow {
TechniqueInfo two_map_bound_info();
}  // namespace sb::shadow

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) { registry.add(sb::shadow::two_map_bound_info()); }
