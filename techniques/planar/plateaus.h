#pragma once
#include "plugin/registry.h"

namespace sb {
// Haines's plateaus (plateaus.cpp), registered by the planar family.
plugin::TechniqueInfo plateaus_info();
}  // namespace sb
