#pragma once
#include "plugin/registry.h"

namespace sb::shadow {
TechniqueInfo hard_shadow_map_info();
TechniqueInfo pcf_box_info();
TechniqueInfo pcf_gauss_info();
TechniqueInfo pcf_jitter_info();
TechniqueInfo pcss_info();
TechniqueInfo blurred_visibility_info();
TechniqueInfo psm_info();
TechniqueInfo lispsm_info();
TechniqueInfo extended_light_maps_info();
TechniqueInfo heidrich_linear_info();
}  // namespace sb::shadow
