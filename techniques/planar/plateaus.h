#pragma once
#include "plugin/registry.h"

namespace sb {
// Haines's plateaus (plateaus.cpp), registered by the planar family.
TechniqueInfo plateaus_info();
}  // namespace sb
