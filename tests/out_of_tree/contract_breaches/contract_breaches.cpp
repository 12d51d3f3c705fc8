// Three hard shadow maps on the shadow-map kit, for check-technique's test:
//   kept_contract  fits the light's frustum and renders the map in every
//                  frame (as SingleMapTechnique does): every check passes;
//   stale_map      renders the map once, in prepare(), under the light of
//                  that moment, and every frame reuses it: its timed frame
//                  leaves out the depth pass, and a moved light is ignored;
//   idle_render    draws V once, in prepare(), and its frames do nothing.
#include <memory>
#include <string>

#include "common/depth_pass.h"
#include "common/light_frustum.h"
#include "common/map_lookup.h"
#include "gl/debug.h"
#include "plugin/registry.h"

namespace contract_breaches {
namespace {

const char* const kHard = R"(
float lit_fraction(vec3 t) { return shadow_tap(t, vec2(0.0)); }
)";

enum class Breach { None, StaleMap, IdleRender };

class HardMap final : public sb::Technique {
 public:
  HardMap(const sb::Params& p, Breach breach)
      : settings_(sb::techniques::depth_map_settings(p)), breach_(breach) {}

  void prepare(const sb::FrameInputs& in) override {
    map_ = sb::techniques::DepthMap(settings_.size, settings_.depth_format);
    lookup_ = sb::techniques::MapLookupPass("hard_lookup", kHard);
    if (breach_ != Breach::None) draw_map(in);
    if (breach_ == Breach::IdleRender) lookup_.draw(in, frustum_, settings_, map_.texture());
    sb::gl::throw_if_errors("contract_breaches prepare");
  }

  void render(const sb::FrameInputs& in, sb::gl::PassTimer& timer) override {
    if (breach_ == Breach::IdleRender) return;
    if (breach_ == Breach::None) {
      auto pass = timer.scope("shadow_map");
      draw_map(in);
    }
    auto pass = timer.scope("lookup");
    lookup_.draw(in, frustum_, settings_, map_.texture());
  }

 private:
  void draw_map(const sb::FrameInputs& in) {
    frustum_ = sb::techniques::fit_light_frustum(*in.scene, in.scene->light.center);
    map_.render(*in.gpu, frustum_, settings_.cull, settings_.bias);
  }

  sb::techniques::DepthMapSettings settings_;
  Breach breach_;
  sb::techniques::LightFrustum frustum_;
  sb::techniques::DepthMap map_;
  sb::techniques::MapLookupPass lookup_;
};

sb::TechniqueInfo info(const std::string& name, Breach breach) {
  return {.name = name,
          .family = "contract_breaches",
          .summary = "a hard shadow map (check-technique's test)",
          .needs = sb::Needs{sb::need::kCasterClosedness},
          .params = sb::techniques::depth_map_params(512),
          .create = [breach](const sb::Params& p) { return std::make_unique<HardMap>(p, breach); }};
}

}  // namespace
}  // namespace contract_breaches

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  using contract_breaches::Breach;
  registry.add(contract_breaches::info("kept_contract", Breach::None));
  registry.add(contract_breaches::info("stale_map", Breach::StaleMap));
  registry.add(contract_breaches::info("idle_render", Breach::IdleRender));
}
