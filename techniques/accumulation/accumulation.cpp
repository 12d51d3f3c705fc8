// accumulation — the rasterised reference of the seeds ("1024-sample
// shadows"): N hard shadow maps from points spread evenly over the area
// light (light_samples.h), their 0/1 visibilities averaged (Heckbert & Herf
// 1997 style).
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <memory>

#include "accumulation/light_samples.h"
#include "common/map_lookup.h"
#include "gl/debug.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "plugin/registry.h"

namespace sb::techniques::accumulation {
namespace {

class Accumulation final : public Technique {
 public:
  explicit Accumulation(const Params& p)
      : samples_(p.get_int("samples")),
        jitter_(p.get_bool("jitter")),
        seed_(static_cast<unsigned>(p.get_int("seed"))),
        map_settings_(depth_map_settings(p)) {}

  void prepare(const FrameInputs& /*in*/) override {
    map_ = DepthMap(map_settings_.size, map_settings_.depth_format);
    // Where the points lie on the light, in its own (s, t): not where the
    // light is, so they may be drawn here; their frusta are fitted per frame.
    points_ = light_sample_layouts(samples_, jitter_, seed_);
    accumulate_ = MapLookupPass("accumulation",
                                "float lit_fraction(vec3 t) { return texture(shadow_map, t); }\n");
    gl::throw_if_errors("accumulation prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    {
      auto pass = timer.scope("accumulate");
      const float zero[4] = {0, 0, 0, 0};
      glClearNamedFramebufferfv(in.visibility_framebuffer, GL_COLOR, 0, zero);
    }
    const float weight = 1.0f / float(points_.size());
    const AreaLight& light = in.scene->light;
    for (size_t i = 0; i < points_.size(); ++i) {
      LightFrustum f;
      {
        auto pass = timer.scope("shadow_maps");
        const glm::vec3 point = light.is_segment()
                                    ? light.segment_end(points_.line[i])
                                    : light.point(points_.square[i].x, points_.square[i].y);
        f = fit_light_frustum(*in.scene, point);
        map_.render(*in.gpu, f, map_settings_.cull, map_settings_.bias);
      }
      auto pass = timer.scope("accumulate");
      glEnable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ONE);
      accumulate_.draw(in, f, map_settings_, map_.texture(), weight);
      glDisable(GL_BLEND);
    }
  }

 private:
  int samples_;
  bool jitter_;
  unsigned seed_;
  DepthMapSettings map_settings_;
  DepthMap map_;
  LightSampleLayouts points_;  // (s, t) on the light
  MapLookupPass accumulate_;
};

}  // namespace
}  // namespace sb::techniques::accumulation

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  using namespace sb;
  using namespace sb::techniques::accumulation;
  auto params = techniques::depth_map_params(1024);
  params.insert(params.begin(),
                {int_param("samples", 256, 1, 65536,
                           "light points: an m×n grid of strata if N = m·n with n <= 2m, "
                           "else the Hammersley set"),
                 bool_param("jitter", true,
                            "jitter each point inside its stratum (Hammersley: one random "
                            "toroidal shift)"),
                 int_param("seed", 1, 0, 2147483647, "jitter seed")});
  registry.add({.name = "accumulation",
                .family = "accumulation",
                .summary = "average of N hard shadow maps from stratified points on the area light",
                .needs = Needs{need::kCasterClosedness},
                .params = std::move(params),
                .create = [](const Params& p) { return std::make_unique<Accumulation>(p); },
                // 64 samples took 10.2× a hard shadow map's job at 320×240 and 7.7× at
                // 640×480 (configs/quick.json, 2-core VM): about 1 + N/8.
                .cost_weight = [](const Params& p) { return 1.0 + p.get_int("samples") / 8.0; }});
}
