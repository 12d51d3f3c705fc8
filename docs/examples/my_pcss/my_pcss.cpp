// my_pcss — stochastic percentage-closer soft shadows: PCSS (Fernando 2005)
// with its blocker search and its filter over Poisson disks of taps, rotated
// per pixel by interleaved gradient noise. Written outside shadowbench as
// docs/writing_a_technique.md ("Building a PCSS variant from the kit
// pieces") says: `shadowbench new-technique my_pcss`, then this
// lit_fraction() and its parameters. Every piece is the kit's
// (shadowbench::shadow_kit, headers common/*.h), the same pcss is built
// from, so the differences between the two are the sampling's alone.
//
// A SingleMapTechnique (common/map_lookup.h): it inherits prepare() (untimed:
// compiles the lookup, allocates the map, calls set_uniforms()) and render()
// (timed: "shadow_map", the frustum fit and depth pass; "lookup", the taps
// below at every pixel).
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/depth_pass.h"
#include "common/glsl_pcf.h"
#include "common/glsl_pcss.h"
#include "common/glsl_rotation_noise.h"
#include "common/map_lookup.h"
#include "common/sample_disks.h"
#include "gl/program.h"
#include "plugin/registry.h"

namespace my_pcss {
namespace {

// The blocker search over a Poisson disk as wide as the search width, then
// PCF over another as wide as the penumbra (a RADIUS of half the width),
// both rotated by the same per-pixel angle.
const char* const kStochasticPcss = R"(
uniform vec2 search_disk[MAX_DISK_TAPS];  // poisson_disk(search_samples, seed)
uniform vec2 filter_disk[MAX_DISK_TAPS];  // poisson_disk(filter_samples, seed)
uniform int search_samples;               // tap COUNTS
uniform int filter_samples;
uniform float light_size;    // world units
uniform float tan_half_fov;  // of the light's frustum
float lit_fraction(vec3 t) {
  float zr = receiver_view_depth();
  mat2 rotation = rotation_by_turns(interleaved_gradient_noise(gl_FragCoord.xy));
  float search_uv = pcss_search_width_uv(light_size, zr, light_depth_range.x, tan_half_fov);
  vec2 blockers = blocker_search_disk(t, search_disk, search_samples, rotation,
                                      vec2(0.5 * search_uv));
  if (blockers.y == 0.0) return 1.0;  // no blocker: lit
  float penumbra_uv = penumbra_width_uv(light_size, zr, blockers.x, tan_half_fov);
  // At least one texel, so that a contact shadow is still filtered.
  float texel = 1.0 / float(textureSize(shadow_map, 0).x);
  return pcf_disk(t, filter_disk, filter_samples, rotation, vec2(max(0.5 * penumbra_uv, texel)));
}
)";

class MyPcss final : public sb::techniques::SingleMapTechnique {
 public:
  // Reads every parameter it declares, and makes no GL call.
  explicit MyPcss(const sb::Params& p)
      : SingleMapTechnique(p, "my_pcss", kStochasticPcss, /*linear_compare=*/true,
                           /*kit_glsl=*/std::string(sb::techniques::kPcssGlsl) +
                               sb::techniques::kPcfGlsl + sb::techniques::kRotationNoiseGlsl),
        search_disk_(
            sb::techniques::poisson_disk(p.get_int("search_samples"), unsigned(p.get_int("seed")))),
        filter_disk_(sb::techniques::poisson_disk(p.get_int("filter_samples"),
                                                  unsigned(p.get_int("seed")))) {}

 protected:
  // Set once, in prepare().
  void set_uniforms(const sb::gl::Program& lookup) const override {
    lookup.set("search_disk", search_disk_);
    lookup.set("filter_disk", filter_disk_);
    lookup.set("search_samples", int(search_disk_.size()));
    lookup.set("filter_samples", int(filter_disk_.size()));
  }
  // Set in every frame: they depend on the light and its frustum.
  void set_light_uniforms(const sb::gl::Program& lookup,
                          const sb::techniques::LightFrustum& frustum,
                          const sb::Scene& scene) const override {
    lookup.set("light_size", 0.5f * (scene.light.width() + scene.light.height()));
    lookup.set("tan_half_fov", frustum.tan_half_fov);
  }

 private:
  std::vector<glm::vec2> search_disk_;
  std::vector<glm::vec2> filter_disk_;
};

sb::TechniqueInfo my_pcss_info() {
  using sb::techniques::kMaxDiskTaps;
  std::vector<sb::ParamSpec> params = {
      sb::int_param("search_samples", 16, 1, kMaxDiskTaps,
                    "blocker-search tap COUNT (a Poisson disk), not a grid side"),
      sb::int_param("filter_samples", 32, 1, kMaxDiskTaps,
                    "PCF tap COUNT (a Poisson disk), not a grid side"),
      sb::int_param("seed", 1, 0, 2147483647, "seed of both Poisson disks"),
      sb::techniques::receiver_plane_param()};
  // On, as in pcss: wide kernels reach past the receiver's own plane.
  params.back().default_value = true;
  for (auto& p : sb::techniques::depth_map_params(2048)) params.push_back(std::move(p));
  return {.name = "my_pcss",
          .family = "my_pcss",
          .summary = "PCSS with rotated Poisson-disk blocker search and filter",
          .needs = sb::Needs{sb::need::kRectangularLight, sb::need::kCasterClosedness},
          .params = std::move(params),
          .create = [](const sb::Params& p) { return std::make_unique<MyPcss>(p); }};
}

}  // namespace
}  // namespace my_pcss

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) { registry.add(my_pcss::my_pcss_info()); }
