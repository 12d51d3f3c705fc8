// evsm — exponential variance shadow maps (Lauritzen & McCool 2008): depth
// z in [0,1] is warped to z' = 2z − 1 and then to exp(c⁺·z') (and, with 4
// components, −exp(−c⁻·z')); each warp's two moments are filtered and
// bounded with Chebyshev, and the smaller bound wins. The warp's steepness
// shrinks the overlap that makes VSM bleed.
//
// The exponents are clamped to what the format holds: exp(2c) must stay
// finite, so c <= 42 for 32f and c <= 5.54 for 16f (ln 65504 / 2).
//
// min_variance is a floor in depth units, carried through each warp (scaled
// by the warp's slope squared).
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <algorithm>
#include <memory>

#include "common/filtered_map.h"
#include "filtered_map/chebyshev.h"
#include "filtered_map/filtered_map_variants.h"

namespace sb::techniques::filtered_map {
namespace {

const char* const kEvsmBasis = R"(
uniform vec2 exponents;
vec4 basis(float z, int layer) {
  float w = 2.0 * z - 1.0;
  float p = exp(exponents.x * w);
  float n = -exp(-exponents.y * w);
  return vec4(p, p * p, n, n * n);
}
)";

const char* const kEvsmLookup = R"(
uniform vec2 exponents;
uniform bool negative_warp;
uniform float min_variance;
uniform float bleeding_reduction;
float lit_fraction(vec3 t) {
  vec4 m = texture(moments, vec3(t.xy, 0.0));
  float w = 2.0 * receiver_depth01() - 1.0;
  float p = exp(exponents.x * w);
  // The variance floor is set in depth units and carried through the warp.
  float p_slope = exponents.x * p;
  float lit = chebyshev_upper_bound(m.xy, p, min_variance * p_slope * p_slope, bleeding_reduction);
  if (negative_warp) {
    float n = -exp(-exponents.y * w);
    float n_slope = exponents.y * n;
    lit = min(lit, chebyshev_upper_bound(m.zw, n, min_variance * n_slope * n_slope,
                                         bleeding_reduction));
  }
  return lit;
}
)";

constexpr float kMaxExponent32F = 42.0f;
constexpr float kMaxExponent16F = 5.54f;

class Evsm final : public FilteredMapTechnique {
 public:
  explicit Evsm(const Params& p)
      : FilteredMapTechnique(p, "evsm",
                             {p.get_int("components") == 4 ? 4 : 2, kEvsmBasis,
                              std::string(kChebyshevGlsl) + kEvsmLookup}),
        negative_warp_(p.get_int("components") == 4),
        bleeding_reduction_(p.get_float("light_bleeding_reduction")),
        min_variance_(p.get_float("min_variance")) {
    const float limit = settings().half_float ? kMaxExponent16F : kMaxExponent32F;
    exponents_ = {std::min(p.get_float("positive_exponent"), limit),
                  std::min(p.get_float("negative_exponent"), limit)};
  }

 protected:
  void set_uniforms(const gl::Program& basis, const gl::Program& lookup) const override {
    basis.set("exponents", exponents_);
    lookup.set("exponents", exponents_);
    lookup.set("negative_warp", negative_warp_ ? 1 : 0);
    lookup.set("min_variance", min_variance_);
    lookup.set("bleeding_reduction", bleeding_reduction_);
  }

 private:
  bool negative_warp_;
  float bleeding_reduction_;
  float min_variance_;
  glm::vec2 exponents_{0.0f};
};

}  // namespace

TechniqueInfo evsm_info() {
  auto params = filtered_map_params(2048, {"32f", "16f"});
  ParamSpec components = int_param("components", 4, 2, 4,
                                   "2: positive exponential warp only; 4: positive and negative");
  components.rule = [](const nlohmann::json& v) {
    return v.get<int>() == 3 ? std::string("2 or 4") : std::string();
  };
  components.rule_doc = "2 or 4";
  params.insert(params.begin(),
                {components,
                 float_param("positive_exponent", 40.0, 0.1, 1000.0,
                             "c+ of exp(c+·(2z−1)); clamped to 42 (32f) or 5.54 (16f)"),
                 float_param("negative_exponent", 5.0, 0.1, 1000.0,
                             "c− of −exp(−c−·(2z−1)); clamped to 42 (32f) or 5.54 (16f)")});
  for (auto& p : bleeding_params(1e-4)) params.push_back(std::move(p));
  return {.name = "evsm",
          .family = "filtered_map",
          .summary = "exponential variance shadow map, 2 or 4 components (Lauritzen & McCool 2008)",
          .needs = Needs{need::kSunOrLocalLight, need::kCasterClosedness},
          .params = std::move(params),
          .create = [](const Params& p) { return std::make_unique<Evsm>(p); }};
}

}  // namespace sb::techniques::filtered_map
