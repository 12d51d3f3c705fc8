// esm — exponential shadow maps (Annen et al. 2008, Salvi 2008): the lit
// fraction is approximated by exp(c·(z_occluder − z_receiver)), clamped to
// 1, and exp(c·z_occluder) filters linearly. Stored as exp(c·z) it overflows
// fp32 once c·z > 88.7 (c = 200: every depth over 0.44). With `log_space`
// (the default) the map keeps z itself and the prefilter works on
// log-sum-exp (separable_filter.h), so no exponential is ever formed above 1.
//
// A larger exponent is sharper and leaks less near contact.
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <memory>

#include "common/filtered_map.h"
#include "filtered_map/filtered_map_variants.h"

namespace sb::techniques::filtered_map {
namespace {

const char* const kLogSpace = R"(
uniform float exponent;
vec4 basis(float z, int layer) { return vec4(z); }
)";

// The map holds z, standing for exp(c·z). Its bilinear filter must average
// exp(c·z): a hardware-filtered z would give exp(c·Σw·z), a geometric mean,
// far below the arithmetic one where depths differ across the footprint. So
// the four texels are fetched and weighed as GL_LINEAR would (texel centres
// at (i+½)/size, edges clamped like the map's GL_CLAMP_TO_EDGE), and summed
// in log space: log Σ w·exp(c·z) = c·m + log Σ w·exp(c·(z − m)), m the
// largest z of a texel with weight > 0, so no exponential exceeds 1 and the
// sum is at least that texel's weight (Salvi 2008).
const char* const kLogSpaceLookup = R"(
uniform float exponent;
float lit_fraction(vec3 t) {
  ivec2 size = textureSize(moments, 0).xy;
  vec2 p = t.xy * vec2(size) - 0.5;
  ivec2 i0 = ivec2(floor(p));
  vec2 f = p - vec2(i0);
  ivec2 last = size - 1;
  ivec2 a = clamp(i0, ivec2(0), last), b = clamp(i0 + 1, ivec2(0), last);
  vec4 z = vec4(texelFetch(moments, ivec3(a.x, a.y, 0), 0).r,
                texelFetch(moments, ivec3(b.x, a.y, 0), 0).r,
                texelFetch(moments, ivec3(a.x, b.y, 0), 0).r,
                texelFetch(moments, ivec3(b.x, b.y, 0), 0).r);
  vec4 w = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
  vec4 live = mix(vec4(-1.0e30), z, greaterThan(w, vec4(0.0)));
  float m = max(max(live.x, live.y), max(live.z, live.w));
  // min(): a texel without weight may lie above m; its exp must not overflow.
  float sum = dot(w, exp(exponent * min(z - m, vec4(0.0))));
  return exp(min(exponent * (m - receiver_depth01()) + log(sum), 0.0));
}
)";

// IEEE exp overflows to +Inf above ln(FLT_MAX) = 88.72; llvmpipe's exp()
// saturates at FLT_MAX instead, which would hide the overflow as a silently
// wrong shadow. Overflow explicitly, so every driver shows the same failure.
const char* const kIeeeExp = R"(
float ieee_exp(float x) { return x > 88.72 ? uintBitsToFloat(0x7f800000u) : exp(x); }
)";

const char* const kLinear = R"(
uniform float exponent;
vec4 basis(float z, int layer) { return vec4(ieee_exp(exponent * z)); }
)";

// clamp_unit, not min(): an overflowed map must show as NaN, not as light.
const char* const kLinearLookup = R"(
uniform float exponent;
float lit_fraction(vec3 t) {
  return clamp_unit(texture(moments, vec3(t.xy, 0.0)).r / ieee_exp(exponent * receiver_depth01()));
}
)";

}  // namespace

BasisShader esm_shader(bool log_space, float exponent) {
  if (log_space) return {1, kLogSpace, kLogSpaceLookup, SeparableFilter::Mode::LogSumExp, exponent};
  return {1, std::string(kIeeeExp) + kLinear, std::string(kIeeeExp) + kLinearLookup,
          SeparableFilter::Mode::Linear, 0.0f};
}

namespace {

class Esm final : public FilteredMapTechnique {
 public:
  explicit Esm(const Params& p)
      : FilteredMapTechnique(p, "esm",
                             esm_shader(p.get_bool("log_space"), p.get_float("exponent"))),
        exponent_(p.get_float("exponent")) {}

 protected:
  void set_uniforms(const gl::Program& basis, const gl::Program& lookup) const override {
    if (basis.has_uniform("exponent")) basis.set("exponent", exponent_);
    lookup.set("exponent", exponent_);
  }

 private:
  float exponent_;
};

}  // namespace

TechniqueInfo esm_info() {
  auto params = filtered_map_params(2048, {"32f", "16f"});
  params.insert(params.begin(),
                {float_param("exponent", 80.0, 0.1, 10000.0,
                             "c in exp(c·(z_occluder − z_receiver)), depths in [0,1]"),
                 bool_param("log_space", true,
                            "store z and filter in log space; false stores exp(c·z) "
                            "(overflows fp32 for c·z > 88.7)")});
  return {.name = "esm",
          .family = "filtered_map",
          .summary = "exponential shadow map, log-space filtered (Annen et al. 2008, Salvi 2008)",
          .needs = Needs{need::kSunOrLocalLight, need::kCasterClosedness},
          .params = std::move(params),
          .create = [](const Params& p) { return std::make_unique<Esm>(p); }};
}

}  // namespace sb::techniques::filtered_map
