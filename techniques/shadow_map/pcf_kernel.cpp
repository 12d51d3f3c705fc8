// pcf_box, pcf_gauss — percentage-closer filtering (Reeves et al. 1987): a
// k×k grid of depth comparisons one texel apart, averaged with box or
// Gaussian weights. Both are the same shader; only the weights differ.
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <memory>

#include "common/kernel.h"
#include "common/map_lookup.h"
#include "shadow_map/shadow_map_variants.h"

namespace sb::techniques::shadow_map {
namespace {

const char* const kKernelPcf = R"(
uniform int radius;
uniform float weights[63];
float lit_fraction(vec3 t) {
  vec2 texel = 1.0 / vec2(textureSize(shadow_map, 0));
  float sum = 0.0;
  for (int y = -radius; y <= radius; ++y) {
    float row = 0.0;
    for (int x = -radius; x <= radius; ++x)
      row += weights[x + radius] * shadow_tap(t, vec2(x, y) * texel);
    sum += weights[y + radius] * row;
  }
  return min(sum, 1.0);
}
)";

class KernelPcf final : public SingleMapTechnique {
 public:
  KernelPcf(const Params& p, KernelShape shape)
      : SingleMapTechnique(p, shape == KernelShape::Box ? "pcf_box" : "pcf_gauss", kKernelPcf,
                           p.get_string("filter") == "bilinear"),
        weights_(kernel_weights(shape, p.get_int("k"),
                                shape == KernelShape::Gauss ? p.get_float("sigma") : 0.0f)) {}

 protected:
  void set_uniforms(const gl::Program& lookup) const override {
    lookup.set("radius", int(weights_.size()) / 2);
    lookup.set("weights", weights_);
  }

 private:
  std::vector<float> weights_;
};

std::vector<ParamSpec> kernel_pcf_params(int default_k, bool gauss) {
  std::vector<ParamSpec> params = {
      kernel_size_param(default_k, "kernel SIDE (odd), not a tap count: k² depth comparisons")};
  if (gauss) params.push_back(kernel_sigma_param());
  params.push_back(choice_param("filter", "nearest", {"nearest", "bilinear"},
                                "bilinear: each tap is a hardware 2x2 PCF"));
  params.push_back(receiver_plane_param());
  for (auto& p : depth_map_params(2048)) params.push_back(std::move(p));
  return params;
}

}  // namespace

TechniqueInfo pcf_box_info() {
  return {
      .name = "pcf_box",
      .family = "shadow_map",
      .summary = "box percentage-closer filtering, k×k taps (Reeves et al. 1987)",
      .needs = Needs{need::kSunOrLocalLight, need::kCasterClosedness},
      .params = kernel_pcf_params(3, false),
      .create = [](const Params& p) { return std::make_unique<KernelPcf>(p, KernelShape::Box); }};
}

TechniqueInfo pcf_gauss_info() {
  return {
      .name = "pcf_gauss",
      .family = "shadow_map",
      .summary = "Gaussian-weighted percentage-closer filtering, k×k taps",
      .needs = Needs{need::kSunOrLocalLight, need::kCasterClosedness},
      .params = kernel_pcf_params(5, true),
      .create = [](const Params& p) { return std::make_unique<KernelPcf>(p, KernelShape::Gauss); }};
}

}  // namespace sb::techniques::shadow_map
