#pragma once
#include "plugin/registry.h"

namespace sb::techniques::shadow_map {
plugin::TechniqueInfo hard_shadow_map_info();
plugin::TechniqueInfo pcf_box_info();
plugin::TechniqueInfo pcf_gauss_info();
plugin::TechniqueInfo pcf_jitter_info();
plugin::TechniqueInfo pcss_info();
plugin::TechniqueInfo blurred_visibility_info();
plugin::TechniqueInfo psm_info();
plugin::TechniqueInfo lispsm_info();
plugin::TechniqueInfo extended_light_maps_info();
plugin::TechniqueInfo heidrich_linear_info();
}  // namespace sb::techniques::shadow_map
