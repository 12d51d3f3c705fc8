// msm — moment shadow maps, Hamburger 4-moment variant (Peters & Klein 2015):
// the map stores (z, z², z³, z⁴); the lookup biases the filtered moments
// towards those of a uniform depth, b' = (1 − α)·b + α·(½, ⅓, ¼, ⅕), finds
// the three-point distribution whose moments they are (a 3×3 Cholesky
// solve and a quadratic) and returns the lit fraction it implies at the
// receiver's depth. Four moments need fp32 here (no 16-bit quantisation).
//
// A larger moment_bias (α) trades light leaks for stability.
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <memory>

#include "common/filtered_map.h"
#include "filtered_map/filtered_map_variants.h"

namespace sb::techniques::filtered_map {
namespace {

const char* const kMsmBasis = R"(
vec4 basis(float z, int layer) {
  float z2 = z * z;
  return vec4(z, z2, z2 * z, z2 * z2);
}
)";

const char* const kMsmLookup = R"(
uniform float moment_bias;
float lit_fraction(vec3 t) {
  // Biased towards the moments of the uniform distribution on [0,1], which
  // keep B positive definite (a point mass at z = 1 mixed with (½,½,½,½)
  // would not: its Hankel matrix is singular, and the solve divides by 0).
  vec4 b = mix(texture(moments, vec3(t.xy, 0.0)), vec4(1.0 / 2.0, 1.0 / 3.0, 1.0 / 4.0, 1.0 / 5.0),
               moment_bias);
  float zf = receiver_depth01();
  // B = [[1, b1, b2], [b1, b2, b3], [b2, b3, b4]] = L·D·Lᵀ; solve B·c = (1, zf, zf²).
  // The bias keeps d2, d3 > 0 in exact arithmetic; fp32 cancellation may not.
  float d2 = max(b.y - b.x * b.x, 1e-9);
  float l32 = (b.z - b.x * b.y) / d2;
  float d3 = max(b.w - b.y * b.y - l32 * l32 * d2, 1e-12);
  float y2 = zf - b.x;
  float y3 = zf * zf - b.y - l32 * y2;
  float c3 = y3 / d3;
  float c2 = y2 / d2 - l32 * c3;
  float c1 = 1.0 - b.x * c2 - b.y * c3;
  // The other two support points: roots of c3·z² + c2·z + c1.
  float root = sqrt(max(c2 * c2 - 4.0 * c3 * c1, 0.0));
  float za = (-c2 - root) / (2.0 * c3);
  float zb = (-c2 + root) / (2.0 * c3);
  float z2 = min(za, zb), z3 = max(za, zb);
  // Each branch divides by differences that are positive there but may
  // round to 0 (foliage: 2 pixels of 480 000 gave Inf); floor them, and let
  // the final clamp absorb the overshoot.
  const float tiny = 1e-7;
  float shadow;
  if (zf <= z2) {
    shadow = 0.0;
  } else if (zf <= z3) {
    shadow = (zf * z3 - b.x * (zf + z3) + b.y) / (max(z3 - z2, tiny) * max(zf - z2, tiny));
  } else {
    shadow = 1.0 - (z2 * z3 - b.x * (z2 + z3) + b.y) / (max(zf - z2, tiny) * max(zf - z3, tiny));
  }
  return clamp_unit(1.0 - shadow);
}
)";

class Msm final : public FilteredMapTechnique {
 public:
  explicit Msm(const Params& p)
      : FilteredMapTechnique(p, "msm", {4, kMsmBasis, kMsmLookup}),
        moment_bias_(p.get_float("moment_bias")) {}

 protected:
  void set_uniforms(const gl::Program& /*basis*/, const gl::Program& lookup) const override {
    lookup.set("moment_bias", moment_bias_);
  }

 private:
  float moment_bias_;
};

}  // namespace

TechniqueInfo msm_info() {
  auto params = filtered_map_params(2048, {"32f"});
  params.insert(params.begin(), float_param("moment_bias", 3e-5, 0.0, 0.5,
                                            "alpha: moments are biased towards a uniform depth"));
  return {.name = "msm",
          .family = "filtered_map",
          .summary = "moment shadow map, Hamburger 4-moment reconstruction (Peters & Klein 2015)",
          .needs = Needs{need::kSunOrLocalLight, need::kCasterClosedness},
          .params = std::move(params),
          .create = [](const Params& p) { return std::make_unique<Msm>(p); }};
}

}  // namespace sb::techniques::filtered_map
