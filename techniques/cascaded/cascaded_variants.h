#pragma once
#include "plugin/registry.h"

namespace sb::techniques::cascaded {
plugin::TechniqueInfo cascaded_shadow_map_info();
plugin::TechniqueInfo sdsm_info();
plugin::TechniqueInfo virtual_shadow_map_info();
}  // namespace sb::techniques::cascaded
