// csm_convolution — convolution shadow maps (Annen et al. 2007): the step
// "lit when the occluder is farther than the receiver", H(d − z), is
// expanded in a Fourier series of M odd terms,
//   H(x) ≈ ½ + 2·Σ_k sin(c_k·x)/c_k,  c_k = (2k − 1)π,
// and sin(c_k(d − z)) = sin(c_k d)·cos(c_k z) − cos(c_k d)·sin(c_k z)
// splits it into basis values of the occluder depth d alone, which the map
// stores (2M of them) and which filter linearly. With d and z in [0,1] the
// series' other jump, at d − z = −1, is out of reach but for an occluder on
// the near plane over a receiver on the far one. Ringing is
// damped with exp(−damping·(k/M)²) per term, and the reconstruction is
// sharpened around ½ (Annen et al.'s 2f − ½ is sharpen = 2).
// The truncated series rises from 0 to 1 over about 1/M around d = z, so a
// lit surface compared with its own depth (a double-sided leaf, an open
// quad: nothing is culled on them) reads ½. As Annen et al. do, the receiver
// is moved towards the light by ε = receiver_offset / (2M) in normalised
// depth before the comparison; occluders closer than ε leak. Their 1/(2M)
// (receiver_offset 1) leaked inside foliage canopies; ½ keeps lit leaves lit
// and gave the lowest error there (docs/shadow_maps.md).
//
// With M terms the map holds 2M basis values, in M/2 layers of four.
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <cmath>
#include <memory>
#include <numbers>

#include "common/filtered_map.h"
#include "filtered_map/filtered_map_variants.h"

namespace sb::techniques::filtered_map {
namespace {

// Layer l holds terms 2l and 2l + 1 (0-based): cos, sin, cos, sin.
const char* const kCsmBasis = R"(
vec4 basis(float z, int layer) {
  float c0 = 3.14159265 * float(4 * layer + 1);
  float c1 = 3.14159265 * float(4 * layer + 3);
  return vec4(cos(c0 * z), sin(c0 * z), cos(c1 * z), sin(c1 * z));
}
)";

const char* const kCsmLookup = R"(
uniform int terms;
uniform float term_weights[32];  // damping / c_k
uniform float sharpen;
uniform float receiver_offset;  // already divided by 2M
float lit_fraction(vec3 t) {
  float z = receiver_depth01() - receiver_offset;
  float f = 0.5;
  for (int k = 0; k < terms; ++k) {
    vec4 m = texture(moments, vec3(t.xy, float(k / 2)));
    vec2 cs = (k % 2 == 0) ? m.xy : m.zw;  // filtered cos(c·d), sin(c·d)
    float c = 3.14159265 * float(2 * k + 1);
    f += 2.0 * term_weights[k] * (cs.y * cos(c * z) - cs.x * sin(c * z));
  }
  return clamp_unit(sharpen * (f - 0.5) + 0.5);
}
)";

class ConvolutionShadowMap final : public FilteredMapTechnique {
 public:
  explicit ConvolutionShadowMap(const Params& p)
      : FilteredMapTechnique(p, "csm_convolution",
                             {2 * p.get_int("terms"), kCsmBasis, kCsmLookup,
                              SeparableFilter::Mode::Linear, 0.0f, /*receivers_in_map=*/false}),
        terms_(p.get_int("terms")),
        sharpen_(p.get_float("sharpen")),
        receiver_offset_(p.get_float("receiver_offset") / float(2 * terms_)) {
    const double damping = p.get_float("damping");
    for (int k = 0; k < terms_; ++k) {
      const double c = std::numbers::pi * double(2 * k + 1);
      const double x = double(k + 1) / double(terms_);
      weights_.push_back(float(std::exp(-damping * x * x) / c));
    }
  }

 protected:
  void set_uniforms(const gl::Program& /*basis*/, const gl::Program& lookup) const override {
    lookup.set("terms", terms_);
    lookup.set("term_weights", weights_);
    lookup.set("sharpen", sharpen_);
    lookup.set("receiver_offset", receiver_offset_);
  }

 private:
  int terms_;
  float sharpen_;
  float receiver_offset_;
  std::vector<float> weights_;
};

}  // namespace

TechniqueInfo csm_convolution_info() {
  // Back faces: a lit surface compared with its own depth sits on the step
  // (f = ½); the far side of a closed caster is safely behind it.
  auto params = filtered_map_params(1024, {"32f", "16f"}, "front");
  params.insert(params.begin(),
                {int_param("terms", 16, 1, 32, "M, Fourier terms (2M basis values per texel)"),
                 float_param("damping", 1.0, 0.0, 100.0,
                             "ringing suppression: term k is weighted exp(-damping·(k/M)²)"),
                 float_param("sharpen", 2.0, 1.0, 16.0,
                             "V = clamp(sharpen·(f − ½) + ½); 2 is Annen et al.'s 2f − ½"),
                 float_param("receiver_offset", 0.5, 0.0, 64.0,
                             "receiver moved towards the light by receiver_offset/(2M) in "
                             "normalised depth (Annen et al. 2007), so lit unculled surfaces "
                             "do not read their own depth as ½")});
  return {.name = "csm_convolution",
          .family = "filtered_map",
          .summary = "convolution shadow map, M Fourier terms (Annen et al. 2007)",
          .needs = Needs{need::kSunOrLocalLight, need::kCasterClosedness},
          .params = std::move(params),
          .create = [](const Params& p) { return std::make_unique<ConvolutionShadowMap>(p); }};
}

}  // namespace sb::techniques::filtered_map
