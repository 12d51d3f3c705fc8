// shadow_map — Williams 1978: one depth map from the light's centre, one
// depth comparison per pixel; visibility is 0 or 1.
//
// The depth pass culls front faces by default (Shypula 2008).
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <memory>

#include "common/map_lookup.h"
#include "shadow_map/shadow_map_variants.h"

namespace sb::techniques::shadow_map {

TechniqueInfo hard_shadow_map_info() {
  return {.name = "shadow_map",
          .family = "shadow_map",
          .summary = "hard shadow map from the light's centre (Williams 1978)",
          .needs = Needs{need::kSunOrLocalLight, need::kCasterClosedness},
          .params = depth_map_params(2048),
          .create = [](const Params& p) {
            return std::make_unique<SingleMapTechnique>(
                p, "shadow_map", "float lit_fraction(vec3 t) { return texture(shadow_map, t); }\n",
                /*linear_compare=*/false);
          }};
}

}  // namespace sb::techniques::shadow_map
