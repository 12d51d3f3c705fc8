#pragma once
// The outer-penumbra family: penumbra maps and smoothies.
#include "plugin/registry.h"

namespace sb::techniques::penumbra_map {
plugin::TechniqueInfo penumbra_maps_info();
plugin::TechniqueInfo smoothies_info();
}  // namespace sb::techniques::penumbra_map
