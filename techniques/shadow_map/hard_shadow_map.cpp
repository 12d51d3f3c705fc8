// shadow_map — Williams 1978: one depth map from the light's centre, one
// depth comparison per pixel; visibility is 0 or 1.
//
// | parameter      | default | meaning                                         |
// |----------------|---------|-------------------------------------------------|
// | size           | 2048    | shadow-map side in texels                       |
// | depth_format   | "32f"   | depth-map format: "32f", "24" or "16"           |
// | constant_bias  | 4       | glPolygonOffset units in the depth pass         |
// | slope_bias     | 2       | glPolygonOffset factor in the depth pass        |
// | cull           | "front" | faces culled in the depth pass (Shypula 2008)   |
// | normal_offset  | 0       | receiver offset along its normal, in texels     |
#include <memory>

#include "common/map_lookup.h"
#include "shadow_map/shadow_map_variants.h"

namespace sb::shadow {

TechniqueInfo hard_shadow_map_info() {
  return {"shadow_map",
          "shadow_map",
          "hard shadow map from the light's centre (Williams 1978)",
          Needs{need::kCasterClosedness},
          depth_map_params(2048),
          [](const Params& p) {
            return std::make_unique<SingleMapTechnique>(
                p, "shadow_map", "float lit_fraction(vec3 t) { return texture(shadow_map, t); }\n",
                /*linear_compare=*/false);
          }};
}

}  // namespace sb::shadow
