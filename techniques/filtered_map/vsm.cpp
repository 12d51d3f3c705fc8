// vsm — variance shadow maps (Donnelly & Lauritzen 2006): the map stores the
// occluder depth's first two moments (z, z²), which filter linearly; the
// lookup bounds the lit fraction with Chebyshev's inequality. Shypula 2008
// times it unfiltered and box- or Gaussian-prefiltered at 9, 13 and 19.
//
// The default map side is Shypula's, 1024²; 16f moments need a
// min_variance of about 1e-3.
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <memory>

#include "common/filtered_map.h"
#include "filtered_map/chebyshev.h"
#include "filtered_map/filtered_map_variants.h"

namespace sb::techniques::filtered_map {
namespace {

const char* const kVsmLookup = R"(
uniform float min_variance;
uniform float bleeding_reduction;
float lit_fraction(vec3 t) {
  vec2 m = texture(moments, vec3(t.xy, 0.0)).xy;
  return chebyshev_upper_bound(m, receiver_depth01(), min_variance, bleeding_reduction);
}
)";

class Vsm final : public FilteredMapTechnique {
 public:
  explicit Vsm(const Params& p)
      : FilteredMapTechnique(
            p, "vsm",
            {2, "vec4 basis(float z, int layer) { return vec4(z, z * z, 0, 0); }\n",
             std::string(kChebyshevGlsl) + kVsmLookup}),
        bleeding_reduction_(p.get_float("light_bleeding_reduction")),
        min_variance_(p.get_float("min_variance")) {}

 protected:
  void set_uniforms(const gl::Program& /*basis*/, const gl::Program& lookup) const override {
    lookup.set("min_variance", min_variance_);
    lookup.set("bleeding_reduction", bleeding_reduction_);
  }

 private:
  float bleeding_reduction_;
  float min_variance_;
};

}  // namespace

std::vector<ParamSpec> bleeding_params(double default_min_variance) {
  return {float_param("light_bleeding_reduction", 0.0, 0.0, 0.99,
                      "Chebyshev bounds below this read 0, the rest rescale to [0,1]"),
          float_param("min_variance", default_min_variance, 0.0, 1.0,
                      "variance floor, in squared [0,1] depth units")};
}

TechniqueInfo vsm_info() {
  auto params = filtered_map_params(1024, {"32f", "16f"});
  for (auto& p : bleeding_params(1e-5)) params.push_back(std::move(p));
  return {.name = "vsm",
          .family = "filtered_map",
          .summary =
              "variance shadow map: filtered (z, z²), Chebyshev bound (Donnelly & Lauritzen 2006)",
          .needs = Needs{need::kSunOrLocalLight, need::kCasterClosedness},
          .params = std::move(params),
          .create = [](const Params& p) { return std::make_unique<Vsm>(p); }};
}

}  // namespace sb::techniques::filtered_map
