// hybrid_reconstruction — shadow volume reconstruction from depth maps
// (McCool 2000; Rahman 2007 §2.4): a depth map of the casters from the
// light's centre, read back to the CPU, its depth discontinuities turned
// into cliff quads (shadow_volume/depth_map_cliffs.h) and counted in the
// stencil with a z-pass rule, as shadow_volume counts its volumes. The map
// sees whatever rasterises, so open and alpha-tested casters (foliage) cast
// volumes too, which shadow_volume, needing closed casters, cannot do. The
// edges of the shadow follow the map's texels; the test is per screen pixel.
//
// Passes: shadow_map (the depth map), read_back (to the CPU), reconstruct
// (the cliffs and caps, on the CPU), upload, stencil, resolve. z-pass only: with the
// camera inside a volume the count is wrong (shadow_volume's z-fail is the
// remedy there; the reconstructed volumes have no caps to count it with).
//
// Parameters, defaults and ranges: docs/parameters.md.
#include "shadow_volume/hybrid_reconstruction.h"

#include <algorithm>
#include <array>
#include <memory>
#include <vector>

#include "common/depth_cliffs.h"
#include "common/depth_pass.h"
#include "gl/debug.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "shadow_volume/caster_volumes.h"
#include "shadow_volume/depth_map_cliffs.h"

namespace sb::techniques::shadow_volume {
namespace {

class HybridReconstruction final : public Technique {
 public:
  explicit HybridReconstruction(const Params& p)
      : settings_(depth_map_settings(p)), threshold_(p.get_float("edge_threshold")) {}

  void prepare(const FrameInputs& in) override {
    bounds_ = in.scene->bounds();  // the scene's, not the light's: immutable
    map_ = DepthMap(settings_.size, settings_.depth_format);
    depths_.assign(size_t(settings_.size) * size_t(settings_.size), 1.0f);
    program_ = gl::Program("hybrid_reconstruction_cliffs", {kVolumeVertex, "", ""});
    resolve_ = gl::Program("hybrid_reconstruction_resolve",
                           {gl::kFullscreenVertexShader, "", kStencilResolveFragment});
    make_vec4_stream(vertices_, vao_);
    gl::throw_if_errors("hybrid_reconstruction prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    LightFrustum frustum;
    {
      auto pass = timer.scope("shadow_map");
      frustum = fit_light_frustum(*in.scene, in.scene->light.center, /*widen_for_light=*/false);
      map_.render(*in.gpu, frustum, settings_.cull, settings_.bias);
    }
    {
      auto pass = timer.scope("read_back");
      glGetTextureImage(map_.texture(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                        GLsizei(depths_.size() * sizeof(float)), depths_.data());
    }
    {
      auto pass = timer.scope("reconstruct");
      cliffs_.clear();
      append_depth_map_cliffs(depths_, settings_.size, frustum, threshold_,
                              past_every_receiver(bounds_, frustum.eye), cliffs_);
    }
    {
      auto pass = timer.scope("upload");
      gl::set_buffer_data(vertices_, GLsizeiptr(cliffs_.size() * sizeof(glm::vec4)), cliffs_.data(),
                          GL_STREAM_DRAW);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glViewport(0, 0, in.width, in.height);
    {
      auto pass = timer.scope("stencil");
      begin_stencil_count(0.0f);
      set_stencil_ops(/*zfail=*/false);
      if (!cliffs_.empty()) {
        program_.use();
        program_.set("view_projection", in.view_projection);
        glBindVertexArray(vao_.get());
        glDrawArrays(GL_TRIANGLES, 0, GLsizei(cliffs_.size()));
      }
      end_stencil_count();
    }
    auto pass = timer.scope("resolve");
    resolve_stencil(in, resolve_);
  }

 private:
  DepthMapSettings settings_;
  float threshold_;
  Bounds bounds_;
  DepthMap map_;
  std::vector<float> depths_;
  std::vector<glm::vec4> cliffs_;
  gl::Program program_, resolve_;
  gl::Buffer vertices_;
  gl::VertexArray vao_;
};

}  // namespace

TechniqueInfo hybrid_reconstruction_info() {
  std::vector<ParamSpec> params;
  // Both faces by default: with the back faces in the map (front culling,
  // shadow_map's default) the caps meet the lit surface at every curved
  // caster's terminator, and camera rays grazing it count a cliff: RMSE
  // 0.0855 against 0.0437 on the 9×9 sphere grid at 800×600.
  for (auto& spec : depth_map_params(1024, "none"))
    if (spec.name != "normal_offset") params.push_back(std::move(spec));
  params.push_back(float_param("edge_threshold", 0.002, 0.0, 10.0,
                               "a step between neighbouring texels is a silhouette when it, and "
                               "its distance from each side's linear extrapolation, exceed this "
                               "fraction of the nearer depth"));
  return {.name = "hybrid_reconstruction",
          .family = "shadow_volume",
          .summary =
              "shadow volumes reconstructed from a depth map's discontinuities on the CPU, counted "
              "in the stencil; open and alpha-tested casters too (McCool 2000)",
          .needs =  // Closedness decides which casters `cull` may cull: asked for
          // always, so that the map does not depend on what else the plan runs.
          Needs{need::kCasterClosedness},
          .params = std::move(params),
          .create = [](const Params& p) { return std::make_unique<HybridReconstruction>(p); }};
}

}  // namespace sb::techniques::shadow_volume
