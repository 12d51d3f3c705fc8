#pragma once
// The outer-penumbra family: penumbra maps and smoothies.
#include "plugin/registry.h"

namespace sb::shadow {
TechniqueInfo penumbra_maps_info();
TechniqueInfo smoothies_info();
}  // namespace sb::shadow
