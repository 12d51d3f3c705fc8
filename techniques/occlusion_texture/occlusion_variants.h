#pragma once
#include "plugin/registry.h"

namespace sb::occlusion {
TechniqueInfo occlusion_textures_info();
}  // namespace sb::occlusion
