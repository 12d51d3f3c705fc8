// pcf — percentage-closer filtering (Reeves et al. 1987) with a k×k box of
// depth comparisons around the lookup, one texel apart.
//
// | parameter      | default  | meaning                                         |
// |----------------|----------|-------------------------------------------------|
// | k              | 3        | kernel side (odd), k*k taps                     |
// | filter         | "nearest"| "bilinear": each tap is a hardware 2×2 PCF      |
// | size, constant_bias, slope_bias, cull, normal_offset: as in shadow_map        |
#include <memory>

#include "common/map_lookup.h"
#include "shadow_map/shadow_map_variants.h"

namespace sb::shadow {
namespace {

const char* const kBoxPcf = R"(
uniform int radius;
float lit_fraction(vec3 t) {
  vec2 texel = 1.0 / vec2(textureSize(shadow_map, 0));
  float sum = 0.0;
  for (int y = -radius; y <= radius; ++y)
    for (int x = -radius; x <= radius; ++x)
      sum += texture(shadow_map, vec3(t.xy + vec2(x, y) * texel, t.z));
  int taps = 2 * radius + 1;
  return sum / float(taps * taps);
}
)";

class PcfBox final : public SingleMapTechnique {
 public:
  explicit PcfBox(const Params& p)
      : SingleMapTechnique(p, "pcf", kBoxPcf, p.get_string("filter") == "bilinear"),
        k_(p.get_int("k")) {}

 protected:
  void set_uniforms(const gl::Program& lookup) const override { lookup.set("radius", k_ / 2); }

 private:
  int k_;
};

}  // namespace

TechniqueInfo pcf_box_info() {
  auto params = depth_map_params(2048);
  params.insert(params.begin(),
                {odd(int_param("k", 3, 1, 63, "kernel side (odd): k*k depth comparisons")),
                 choice_param("filter", "nearest", {"nearest", "bilinear"},
                              "bilinear: each tap is a hardware 2x2 PCF")});
  return {
      "pcf",   "shadow_map",      "box percentage-closer filtering, k×k taps (Reeves et al. 1987)",
      Needs{}, std::move(params), [](const Params& p) { return std::make_unique<PcfBox>(p); }};
}

}  // namespace sb::shadow
