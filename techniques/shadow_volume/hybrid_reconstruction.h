#pragma once
#include "plugin/registry.h"

namespace sb::shadow {
// hybrid_reconstruction: shadow volumes rebuilt from a depth map
// (hybrid_reconstruction.cpp).
plugin::TechniqueInfo hybrid_reconstruction_info();
}  // namespace sb::shadow
