#pragma once
#include <vector>

#include "common/filtered_map.h"
#include "plugin/registry.h"

namespace sb::techniques::filtered_map {
plugin::TechniqueInfo vsm_info();
plugin::TechniqueInfo esm_info();
plugin::TechniqueInfo evsm_info();
plugin::TechniqueInfo msm_info();
plugin::TechniqueInfo csm_convolution_info();
// esm's map and lookup GLSL (exposed for tests that run the lookup alone).
BasisShader esm_shader(bool log_space, float exponent);
// light_bleeding_reduction and min_variance, shared by vsm and evsm.
std::vector<core::ParamSpec> bleeding_params(double default_min_variance);
}  // namespace sb::techniques::filtered_map
