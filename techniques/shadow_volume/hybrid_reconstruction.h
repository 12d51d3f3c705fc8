#pragma once
#include "plugin/registry.h"

namespace sb::techniques::shadow_volume {
// hybrid_reconstruction: shadow volumes rebuilt from a depth map
// (hybrid_reconstruction.cpp).
plugin::TechniqueInfo hybrid_reconstruction_info();
}  // namespace sb::techniques::shadow_volume
