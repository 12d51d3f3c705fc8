// extended_light_maps — Brabec & Seidel 2000 (Rahman 2007 §2.5): one pass
// from the light writes the shadow channel and a light channel together
// (shadow_map/extended_light_map.h), and the lookup compares depths as the
// hardware of the time did, in the 8-bit alpha channel, or as today's
// shadow_map does, in a 24- or 32-bit depth buffer. The variants measure in
// one run what the single pass saves (`light_channel`: same_pass against
// separate_pass against none) and what 8-bit depth costs (`shadow_channel`:
// acne, or with `alpha_bias` the light leaks that cure it).
//
// Parameters, defaults and ranges: docs/parameters.md.
#include <memory>
#include <string>

#include "common/map_lookup.h"
#include "gl/debug.h"
#include "shadow_map/extended_light_map.h"
#include "shadow_map/shadow_map_variants.h"

namespace sb::techniques::shadow_map {
namespace {

const char* const kDepthLookup = R"(
float lit_fraction(vec3 t) { return texture(shadow_map, t); }
)";

const char* const kAlpha8Lookup = R"(
uniform float alpha_bias;
float lit_fraction(vec3 t) { return alpha8_lit(t, alpha_bias); }
)";

ShadowChannel shadow_channel_from(const std::string& s) {
  return s == "alpha8" ? ShadowChannel::Alpha8
         : s == "24"   ? ShadowChannel::Depth24
                       : ShadowChannel::Depth32f;
}

LightChannel light_channel_from(const std::string& s) {
  return s == "same_pass"       ? LightChannel::SamePass
         : s == "separate_pass" ? LightChannel::SeparatePass
                                : LightChannel::None;
}

class ExtendedLightMaps final : public Technique {
 public:
  explicit ExtendedLightMaps(const Params& p) : alpha_bias_(p.get_float("alpha_bias")) {
    settings_.size = p.get_int("size");
    settings_.shadow = shadow_channel_from(p.get_string("shadow_channel"));
    settings_.light = light_channel_from(p.get_string("light_channel"));
    settings_.bias = {p.get_float("constant_bias"), p.get_float("slope_bias")};
    settings_.cull = cull_mode_from_string(p.get_string("cull"));
    lookup_settings_.size = settings_.size;
  }

  void prepare(const FrameInputs& /*in*/) override {
    map_ = ExtendedLightMap(settings_);
    const bool alpha = settings_.shadow == ShadowChannel::Alpha8;
    lookup_ = MapLookupPass("extended_light_maps_lookup",
                            alpha ? std::string(kAlpha8LookupGlsl) + kAlpha8Lookup : kDepthLookup);
    if (alpha) lookup_.program().set("alpha_bias", alpha_bias_);
    gl::throw_if_errors("extended_light_maps prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    LightFrustum frustum;
    {
      // The pass the published system runs: shadow and light channels at
      // once (or the shadow channel alone).
      auto pass = timer.scope("light_map");
      frustum = fit_light_frustum(*in.scene, in.scene->light.center);
      map_.render_shadow_channel(*in.gpu, frustum);
    }
    if (settings_.light == LightChannel::SeparatePass) {
      auto pass = timer.scope("light_channel");
      map_.render_light_channel(*in.gpu, frustum);
    }
    auto pass = timer.scope("lookup");
    glBindTextureUnit(4, map_.color());
    lookup_.draw(in, frustum, lookup_settings_, map_.depth());
  }

 private:
  float alpha_bias_;
  ExtendedLightMapSettings settings_;
  DepthMapSettings lookup_settings_;  // no normal offset, no receiver plane
  ExtendedLightMap map_;
  MapLookupPass lookup_;
};

}  // namespace

TechniqueInfo extended_light_maps_info() {
  return {
      .name = "extended_light_maps",
      .family = "shadow_map",
      .summary =
          "extended light maps: shadow and light channels in one pass from the light, depth in the "
          "8-bit alpha channel or a 24/32-bit depth buffer (Brabec & Seidel 2000)",
      .needs = Needs{need::kCasterClosedness},
      .params = {as_map_size(int_param("size", 1024, 16, 16384, "light-map side in texels")),
                 choice_param(
                     "shadow_channel", "alpha8", {"alpha8", "24", "32f"},
                     "where the depth is compared: 8-bit linear depth in the alpha channel (as "
                     "published), or a 24-bit or 32-bit float depth buffer"),
                 choice_param(
                     "light_channel", "same_pass", {"same_pass", "separate_pass", "none"},
                     "the light channel (irradiance) written in the shadow channel's pass, in a "
                     "second pass over the scene, or not at all"),
                 float_param("alpha_bias", 1.0, 0.0, 255.0,
                             "8-bit steps a receiver may lie behind the stored depth and stay lit "
                             "(alpha8 only)"),
                 float_param("constant_bias", 4.0, -1e6, 1e6, "glPolygonOffset units (map pass)"),
                 float_param("slope_bias", 2.0, -1e3, 1e3, "glPolygonOffset factor (map pass)"),
                 choice_param(
                     "cull", "none", {"none", "back", "front"},
                     "faces culled when rendering the map, closed casters only (none: every face "
                     "the light sees, as published)")},
      .create = [](const Params& p) { return std::make_unique<ExtendedLightMaps>(p); }};
}

}  // namespace sb::techniques::shadow_map
