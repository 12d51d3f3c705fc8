#pragma once
#include "plugin/registry.h"

namespace sb::techniques::occlusion_texture {
plugin::TechniqueInfo occlusion_textures_info();
}  // namespace sb::techniques::occlusion_texture
