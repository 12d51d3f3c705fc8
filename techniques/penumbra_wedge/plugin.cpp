// The penumbra-wedge family: one registration line per variant.
#include "penumbra_wedge/wedge_variants.h"

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  registry.add(sb::techniques::penumbra_wedge::penumbra_wedges_info());
  registry.add(sb::techniques::penumbra_wedge::penumbra_wedges_blend_info());
}
