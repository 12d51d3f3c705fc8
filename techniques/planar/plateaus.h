#pragma once
#include "plugin/registry.h"

namespace sb::techniques::planar {
// Haines's plateaus (plateaus.cpp), registered by the planar family.
plugin::TechniqueInfo plateaus_info();
}  // namespace sb::techniques::planar
