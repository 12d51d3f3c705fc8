// my_pcf — a hard shadow map filtered by a k×k box of depth comparisons
// (percentage-closer filtering, Reeves et al. 1987), written as a technique
// built outside shadowbench: on the plugin API and the shadow-map kit
// (shadowbench::shadow_kit, headers common/*.h) alone.
//
// The kit gives it the built-in pcf_box's light frustum, depth pass, biases,
// culling and map lookup; only the filter, lit_fraction() below, is its own.
// Written as the same filter, its visibility equals pcf_box's for the same
// parameters (shadowbench's tests check that the RMSEs agree to 1e-6).
//
// Per frame, in render() (timed):
//   shadow_map — fit the light's frustum to the casters, render the depth map;
//   lookup     — at every G-buffer pixel, k×k comparisons around its point in
//                the map, one texel apart, averaged.
// prepare() (untimed) only compiles and allocates: the frustum depends on
// the light, so it is fitted in every frame (plugin/technique.h).
#include <memory>
#include <utility>
#include <vector>

#include "common/depth_pass.h"
#include "common/kernel.h"
#include "common/light_frustum.h"
#include "common/map_lookup.h"
#include "gl/debug.h"
#include "plugin/registry.h"

namespace my_pcf {
namespace {

// The map lookup (common/map_lookup.h) calls lit_fraction(t) with t the
// pixel's point in the map's [0,1]³ texture space; shadow_tap(t, offset)
// is one depth comparison `offset` (in uv) away from it: 1 lit, 0 shadowed.
const char* const kBoxPcf = R"(
uniform int radius;
float lit_fraction(vec3 t) {
  vec2 texel = 1.0 / vec2(textureSize(shadow_map, 0));
  float lit = 0.0;
  for (int y = -radius; y <= radius; ++y)
    for (int x = -radius; x <= radius; ++x) lit += shadow_tap(t, vec2(x, y) * texel);
  float side = float(2 * radius + 1);
  return lit / (side * side);
}
)";

class MyPcf final : public sb::Technique {
 public:
  // Reads every parameter it declares, and makes no GL call.
  explicit MyPcf(const sb::Params& p)
      : settings_(sb::techniques::depth_map_settings(p)), radius_(p.get_int("k") / 2) {}

  void prepare(const sb::FrameInputs& /*in*/) override {
    map_ = sb::techniques::DepthMap(settings_.size, settings_.depth_format);
    lookup_ = sb::techniques::MapLookupPass("my_pcf_lookup", kBoxPcf);
    lookup_.program().set("radius", radius_);
    sb::gl::throw_if_errors("my_pcf prepare");
  }

  void render(const sb::FrameInputs& in, sb::gl::PassTimer& timer) override {
    sb::techniques::LightFrustum frustum;
    {
      auto pass = timer.scope("shadow_map");
      frustum = sb::techniques::fit_light_frustum(*in.scene, in.scene->light.center);
      map_.render(*in.gpu, frustum, settings_.cull, settings_.bias);
    }
    auto pass = timer.scope("lookup");
    lookup_.draw(in, frustum, settings_, map_.texture());
  }

 private:
  sb::techniques::DepthMapSettings settings_;
  int radius_;
  sb::techniques::DepthMap map_;
  sb::techniques::MapLookupPass lookup_;
};

sb::TechniqueInfo my_pcf_info() {
  // k, then the depth map's own parameters (size, depth_format,
  // constant_bias, slope_bias, cull, normal_offset) with pcf_box's defaults.
  std::vector<sb::ParamSpec> params = {
      sb::techniques::kernel_size_param(3, "kernel side (odd): k*k depth comparisons")};
  for (auto& p : sb::techniques::depth_map_params(2048)) params.push_back(std::move(p));
  return {.name = "my_pcf",
          .family = "my_pcf",
          .summary = "k×k box PCF on the shadow-map kit, pcf_box's filter as a plugin",
          // The depth pass culls only casters known to be closed, and they are
          // known only when a technique asks (common/depth_pass.h).
          .needs = sb::Needs{sb::need::kCasterClosedness},
          .params = std::move(params),
          .create = [](const sb::Params& p) { return std::make_unique<MyPcf>(p); }};
}

}  // namespace
}  // namespace my_pcf

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) { registry.add(my_pcf::my_pcf_info()); }
