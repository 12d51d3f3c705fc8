#pragma once
#include "plugin/registry.h"

namespace sb::occlusion {
plugin::TechniqueInfo occlusion_textures_info();
}  // namespace sb::occlusion
