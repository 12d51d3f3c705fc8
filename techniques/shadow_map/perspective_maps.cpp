// psm and lispsm — one hard shadow map from the light's centre, warped so
// that its texels are dense near the camera (shadow_map/perspective_warp.h):
// perspective shadow maps (Stamminger & Drettakis 2002) and light-space
// perspective shadow maps (Wimmer et al. 2004). The lookup is shadow_map's:
// one depth comparison, V = 0 or 1; only the map's projection differs, fitted
// in every frame from the camera, the light and the scene (timed, in the
// map's pass).
//
// The normal offset is not offered: a warped map's texels have no one size.
#include <memory>
#include <string>
#include <vector>

#include "common/convex_body.h"
#include "common/map_lookup.h"
#include "shadow_map/perspective_warp.h"
#include "shadow_map/shadow_map_variants.h"

namespace sb::techniques::shadow_map {
namespace {

const char* const kHardCompare = "float lit_fraction(vec3 t) { return texture(shadow_map, t); }\n";

std::vector<ParamSpec> warped_map_params() {
  std::vector<ParamSpec> specs;
  for (auto& spec : depth_map_params(2048))
    if (spec.name != "normal_offset") specs.push_back(std::move(spec));
  return specs;
}

class PerspectiveMap : public SingleMapTechnique {
 public:
  PerspectiveMap(const Params& p, const std::string& name, float n_scale)
      : SingleMapTechnique(p, name, kHardCompare, /*linear_compare=*/false),
        lispsm_(name == "lispsm"),
        n_scale_(n_scale) {}

 protected:
  void prepare(const FrameInputs& in) override {
    SingleMapTechnique::prepare(in);
    // The meshes' boxes are scene data: no light or camera moves them.
    boxes_ = mesh_boxes(*in.scene);
  }

  LightFrustum fit(const FrameInputs& in) const override {
    const CameraView camera{in.view, in.projection};
    return lispsm_ ? fit_lispsm(*in.scene, boxes_, camera, n_scale_)
                   : fit_psm(*in.scene, boxes_, camera);
  }

 private:
  bool lispsm_;
  float n_scale_;
  std::vector<Bounds> boxes_;
};

}  // namespace

TechniqueInfo psm_info() {
  return {
      .name = "psm",
      .family = "shadow_map",
      .summary =
          "perspective shadow map: the hard map in the camera's post-perspective space, with the "
          "inverted projection for lights behind the camera (Stamminger & Drettakis 2002)",
      .needs = Needs{need::kCasterClosedness},
      .params = warped_map_params(),
      .create = [](const Params& p) { return std::make_unique<PerspectiveMap>(p, "psm", 1.0f); }};
}

TechniqueInfo lispsm_info() {
  std::vector<ParamSpec> params = warped_map_params();
  params.push_back(float_param("n_scale", 1.0, 0.01, 1e4,
                               "the warp's near distance over the paper's n_opt (larger: nearer "
                               "to the uniform shadow_map)"));
  return {.name = "lispsm",
          .family = "shadow_map",
          .summary =
              "light-space perspective shadow map with the paper's n_opt (Wimmer, Scherzer & "
              "Purgathofer 2004)",
          .needs = Needs{need::kCasterClosedness},
          .params = std::move(params),
          .create = [](const Params& p) {
            return std::make_unique<PerspectiveMap>(p, "lispsm", p.get_float("n_scale"));
          }};
}

}  // namespace sb::techniques::shadow_map
