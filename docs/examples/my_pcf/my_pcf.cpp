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
// It is a SingleMapTechnique (common/map_lookup.h), the kit's base for
// every technique made of one depth map and one lookup (shadow_map, the PCF
// kernels, pcss): it inherits prepare() and render(), and gives only its
// lit_fraction() GLSL and its uniforms. What the inherited methods do:
// per frame, in render() (timed):
//   shadow_map — fit the light's frustum to the casters, render the depth map;
//   lookup     — at every G-buffer pixel, k×k comparisons around its point in
//                the map, one texel apart, averaged.
// prepare() (untimed) only compiles the lookup, allocates the map and calls
// set_uniforms(): the frustum depends on the light, so it is fitted in every
// frame (plugin/technique.h).
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/depth_pass.h"
#include "common/glsl_pcf.h"
#include "common/kernel.h"
#include "common/map_lookup.h"
#include "gl/program.h"
#include "plugin/registry.h"

namespace my_pcf {
namespace {

// The map lookup (common/map_lookup.h) calls lit_fraction(t) with t the
// pixel's point in the map's [0,1]³ texture space. pcf_grid (the kit's
// common/glsl_pcf.h, passed as kit_glsl below) averages shadow_tap, one depth
// comparison (1 lit, 0 shadowed), over a (2·radius+1)² grid. Other kit
// pieces to start from: a rotated Poisson disk,
//   pcf_disk(t, disk, n, rotation_by_turns(interleaved_gradient_noise(
//            gl_FragCoord.xy)), radius_uv)
// with `uniform vec2 disk[MAX_DISK_TAPS]` set from poisson_disk(n, seed)
// (common/sample_disks.h, common/glsl_rotation_noise.h); or PCSS's blocker
// search and penumbra width (common/glsl_pcss.h).
const char* const kBoxPcf = R"(
uniform int radius;
float lit_fraction(vec3 t) {
  // Taps one texel apart.
  return pcf_grid(t, radius, 1.0 / vec2(textureSize(shadow_map, 0)));
}
)";

class MyPcf final : public sb::techniques::SingleMapTechnique {
 public:
  // Reads every parameter it declares, and makes no GL call: the base reads
  // the depth map's parameters; prepare() compiles the lookup from this GLSL.
  explicit MyPcf(const sb::Params& p)
      : SingleMapTechnique(p, "my_pcf", kBoxPcf, /*linear_compare=*/false,
                           /*kit_glsl=*/sb::techniques::kPcfGlsl),
        radius_(p.get_int("k") / 2) {}

 protected:
  // Uniforms that depend on the parameters only: set once, in prepare().
  void set_uniforms(const sb::gl::Program& lookup) const override { lookup.set("radius", radius_); }

 private:
  int radius_;
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
