#pragma once
// The filterable shadow maps (VSM, ESM, EVSM, MSM, convolution maps) share
// one pipeline; each variant supplies only its GLSL:
//   1. "shadow_map": a depth map from the light's centre (DepthMap);
//   2. "moments":    every texel's occluder depth z (linear, in [0,1]) turned
//                    into the variant's basis values (z, z²; exp(c·z); ...),
//                    stored in 16- or 32-bit float layers;
//   3. "prefilter":  an optional separable box or Gaussian filter over them;
//   4. "lookup":     visibility reconstructed from the bilinearly filtered
//                    basis values at the receiver's depth.
// The light frustum, and the depth range the basis values are computed in,
// are fitted in every frame (plugin/technique.h: prepare() must not depend on
// the light).
//
// What the kit guarantees here (shadowbench::shadow_kit, installed):
//   in     the parameters of filtered_map_params() and a BasisShader;
//   out    V in every pixel of the visibility target, as map_lookup.h;
//   GL     prepare() makes the depth map, the basis array (channels rounded
//          up to layers of 4, 16- or 32-bit float, bilinear), the filter
//          and two programs. render() leaves the state the lookup's draw()
//          leaves (map_lookup.h), the basis array on unit 4;
//   cost   per frame, timed as "shadow_map", "moments", "prefilter" (only
//          with a prefilter and k > 1) and "lookup": the depth pass, one
//          full-screen pass per layer over size² texels, the separable
//          filter's 2 × layers passes of k taps, and the lookup; memory the
//          depth map plus size² × layers × 4 channels (2 or 4 bytes each;
//          1 or 2 channels for 1- or 2-channel bases), twice with a
//          prefilter.
#include <optional>
#include <string>
#include <vector>

#include "common/depth_pass.h"
#include "common/kernel.h"
#include "common/map_lookup.h"
#include "common/separable_filter.h"

namespace sb::techniques {

// The parameters of a filterable map (filtered_map_params()), read once.
struct FilteredMapSettings {
  DepthMapSettings depth;
  bool half_float = false;               // "16f" storage of the basis values
  std::optional<KernelShape> prefilter;  // none, box or gauss
  int k = 1;
  float sigma = 0.0f;
};

// depth_map_params + format (from `formats`, the first the default),
// prefilter, k, sigma. Mean-based reconstructions want the light-facing
// surfaces in the map (cull "back"): with back faces the occluder depth sits
// just above the receiver, and exp/Chebyshev bounds leak light in umbrae.
std::vector<core::ParamSpec> filtered_map_params(int default_size,
                                                 const std::vector<std::string>& formats,
                                                 const std::string& default_cull = "back");
FilteredMapSettings filtered_map_settings(const core::Params& p);

// What a filterable-map variant supplies: its basis values and its
// reconstruction, as GLSL.
struct BasisShader {
  int channels = 1;  // basis values per texel, 1..32 (layers of 4 beyond 4)
  // Defines `vec4 basis(float z, int layer)`: the values stored for an
  // occluder at depth z in [0,1] (1: nothing, the far plane), layer by layer.
  std::string basis_glsl;
  // Defines `float lit_fraction(vec3 t)` (see map_lookup.h); it may read
  // `moments` (sampler2DArray, bilinear, unit 4) and `receiver_depth01()`.
  std::string lit_fraction_glsl;
  SeparableFilter::Mode filter_mode = SeparableFilter::Mode::Linear;
  float filter_exponent = 0.0f;  // for LogSumExp
  // Draw the non-casters (the ground) into the map too. Reconstructions from
  // a mean (Chebyshev, exp) assume the receiver is the farthest surface under
  // the filter; an empty texel reads as the far plane and breaks that.
  // Convolution maps filter the step itself and need no receiver.
  bool receivers_in_map = true;
};

// A whole filterable-map technique (VSM, ESM, EVSM, MSM, convolution maps):
// depth map, basis values, optional prefilter and lookup, timed as
// "shadow_map", "moments", "prefilter" and "lookup".
// cost: per frame the depth pass, one full-screen pass per basis layer over
// size² texels, 2 × layers filter passes of k taps (with a prefilter) and the
// lookup; memory the depth map plus size² × layers × 4 channels of 2 or 4
// bytes, twice with a prefilter.
class FilteredMapTechnique : public plugin::Technique {
 public:
  FilteredMapTechnique(const core::Params& p, std::string name, BasisShader shader);
  void prepare(const plugin::FrameInputs& in) override;
  void render(const plugin::FrameInputs& in, gl::PassTimer& timer) override;

 protected:
  // The variant's own uniforms, set once in prepare().
  virtual void set_uniforms(const gl::Program& /*basis*/, const gl::Program& /*lookup*/) const {}
  const FilteredMapSettings& settings() const { return settings_; }

 private:
  std::string name_;
  BasisShader shader_;
  FilteredMapSettings settings_;
  int layers_ = 1;
  DepthMap map_;
  gl::Texture moments_;
  std::vector<gl::Framebuffer> moment_layers_;
  gl::Program basis_;
  std::optional<SeparableFilter> filter_;
  MapLookupPass lookup_;
};

}  // namespace sb::techniques
