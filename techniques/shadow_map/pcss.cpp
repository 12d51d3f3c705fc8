// pcss — percentage-closer soft shadows (Fernando 2005), the variable-width
// PCF of Shypula 2008: a blocker search over the part of the map through
// which the receiver sees the light, then a PCF whose width is the penumbra
// the average blocker depth predicts for a light of the scene's size:
//   search width (near plane) = L · (z_r − n) / z_r
//   penumbra width (receiver) = L · (z_r − z_b) / z_b
// with L the light's side, n the near plane, z_r and z_b the receiver's and
// the blockers' distances along the light's axis. Under the sun (one
// orthographic map) the light is a cone of angular diameter α from every
// receiver: search width spread·(z_r − n), penumbra width spread·(z_r − z_b)
// with spread = 2·tan(α/2), both in world units across the map.
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <cmath>
#include <memory>
#include <string>

#include "common/glsl_pcf.h"
#include "common/glsl_pcss.h"
#include "common/map_lookup.h"
#include "shadow_map/shadow_map_variants.h"

namespace sb::techniques::shadow_map {
namespace {

// The pieces are the kit's (common/glsl_pcss.h, common/glsl_pcf.h); only
// the choice of grids and the smallest filter are pcss's own.
const char* const kPcssLitFraction = R"(
uniform int search_radius;
uniform int filter_radius;
uniform float light_size;     // world units
uniform float tan_half_fov;   // of the light's frustum
uniform float search_texels;  // 0: derived
uniform float min_filter_texels;
uniform float sun_spread;     // under the sun: 2·tan(α/2)
uniform float map_side;       // under the sun: the orthographic map's side, world units
float lit_fraction(vec3 t) {
  vec2 texel = 1.0 / vec2(textureSize(depth_map, 0));
  float zr = receiver_view_depth();
  float search_uv = search_texels > 0.0 ? search_texels * texel.x
      : light_orthographic
      ? max(sun_search_width_uv(sun_spread, zr, light_depth_range.x, map_side), texel.x)
      : pcss_search_width_uv(light_size, zr, light_depth_range.x, tan_half_fov);
  vec2 blockers = blocker_search_grid(t, search_radius, search_uv);
  if (blockers.y == 0.0) return 1.0;
  float penumbra_uv = light_orthographic
      ? sun_penumbra_width_uv(sun_spread, zr, blockers.x, map_side)
      : penumbra_width_uv(light_size, zr, blockers.x, tan_half_fov);
  // A width: the kernel's radius is half of it.
  return pcf_grid_radius(t, filter_radius, max(0.5 * penumbra_uv, min_filter_texels * texel.x));
}
)";

class Pcss final : public SingleMapTechnique {
 public:
  explicit Pcss(const Params& p)
      : SingleMapTechnique(p, "pcss", kPcssLitFraction, /*linear_compare=*/true,
                           std::string(kPcssGlsl) + kPcfGlsl),
        search_radius_(p.get_int("search_taps") / 2),
        filter_radius_(p.get_int("filter_taps") / 2),
        search_texels_(p.get_float("search_texels")),
        min_filter_texels_(p.get_float("min_filter_texels")) {}

 protected:
  void set_uniforms(const gl::Program& lookup) const override {
    lookup.set("search_radius", search_radius_);
    lookup.set("filter_radius", filter_radius_);
    lookup.set("search_texels", search_texels_);
    lookup.set("min_filter_texels", min_filter_texels_);
  }
  void set_light_uniforms(const gl::Program& lookup, const LightFrustum& frustum,
                          const Scene& scene) const override {
    // A rectangular light: the mean of its sides (the scenes' lights are square).
    lookup.set("light_size", 0.5f * (scene.light.width() + scene.light.height()));
    lookup.set("tan_half_fov", frustum.tan_half_fov);
    // Under the sun: its cone, and the orthographic map's side.
    lookup.set("sun_spread", 2.0f * std::tan(0.5f * scene.light.angular_diameter));
    lookup.set("map_side", 2.0f * frustum.half_extent);
  }

 private:
  int search_radius_;
  int filter_radius_;
  float search_texels_;
  float min_filter_texels_;
};

}  // namespace

TechniqueInfo pcss_info() {
  std::vector<ParamSpec> params = {
      odd(int_param("search_taps", 3, 1, 31,
                    "blocker-search grid SIDE (odd), not a tap count: side² taps")),
      with_sentinel(float_param("search_texels", 0.0, 0.0, 4096.0,
                                "blocker-search full width (not radius) in texels; 0: from the "
                                "light's size and the receiver's depth"),
                    0.0),
      odd(int_param("filter_taps", 5, 1, 31,
                    "PCF grid SIDE (odd), not a tap count: side² taps, spread over the penumbra")),
      float_param("min_filter_texels", 1.0, 0.0, 64.0,
                  "smallest PCF radius (half its width), in texels"),
      receiver_plane_param()};
  // On by default: PCSS filters reach far more texels than a small PCF, and
  // without it the wide kernels shadow lit receivers (sphere grid, light 2,
  // 1024² map: penumbra RMSE 0.194 without, 0.155 with).
  params.back().default_value = true;
  for (auto& p : depth_map_params(2048)) params.push_back(std::move(p));
  return {.name = "pcss",
          .family = "shadow_map",
          .summary =
              "percentage-closer soft shadows: blocker search, then PCF as wide as the penumbra "
              "(Fernando 2005)",
          .needs = Needs{need::kSunOrLocalLight, need::kRectangularLight, need::kCasterClosedness},
          .params = std::move(params),
          .create = [](const Params& p) { return std::make_unique<Pcss>(p); }};
}

}  // namespace sb::techniques::shadow_map
