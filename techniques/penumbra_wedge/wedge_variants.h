#pragma once
// The penumbra-wedge family: plain wedges, and Forest et al.'s blending.
#include <vector>

#include "plugin/registry.h"

namespace sb::techniques::penumbra_wedge {
plugin::TechniqueInfo penumbra_wedges_info();
plugin::TechniqueInfo penumbra_wedges_blend_info();
// The umbra volumes' and silhouettes' parameters, which both share.
std::vector<core::ParamSpec> umbra_params();
}  // namespace sb::techniques::penumbra_wedge
