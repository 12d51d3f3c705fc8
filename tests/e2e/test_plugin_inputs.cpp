// What FrameInputs hands a technique beyond positions and normals: the
// receiver plane it asked for (needs.planar_receiver) and the G-buffer's
// shading normal and albedo.
#include <gtest/gtest.h>

#include "e2e_util.h"
#include "gl/gl.h"
#include "plugin/registry.h"

namespace sb::test {

using core::Params;
using plugin::FrameInputs;
using plugin::Needs;
using plugin::Registry;
using plugin::Technique;

namespace {

struct Seen {
  bool has_plane = false;
  glm::vec4 plane{0.0f};
  GLint albedo_format = 0, shading_normal_format = 0;
};

class ReadsItsInputs final : public Technique {
 public:
  explicit ReadsItsInputs(Seen* seen) : seen_(seen) {}
  void prepare(const FrameInputs& in) override {
    seen_->has_plane = in.has_receiver_plane;
    seen_->plane = in.receiver_plane;
    glGetTextureLevelParameteriv(in.gbuffer_albedo, 0, GL_TEXTURE_INTERNAL_FORMAT,
                                 &seen_->albedo_format);
    glGetTextureLevelParameteriv(in.gbuffer_shading_normal, 0, GL_TEXTURE_INTERNAL_FORMAT,
                                 &seen_->shading_normal_format);
  }
  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    auto pass = timer.scope("clear");
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glClearColor(1, 1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
  }

 private:
  Seen* seen_;
};

TEST(PluginInputs, TheReceiverPlaneAndTheGBuffersShadingInputsReachTheTechnique) {
  Seen seen;
  Registry registry;
  registry.add({"reads_inputs",
                "test",
                "reads its inputs",
                Needs{plugin::need::kPlanarReceiver},
                {},
                [&seen](const Params&) { return std::make_unique<ReadsItsInputs>(&seen); }});
  const nlohmann::json config = {{"name", "inputs"},
                                 {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 2}}}}}},
                                 {"techniques", {"reads_inputs"}},
                                 {"resolutions", {{32, 24}}},
                                 {"frames", {{"warmup", 0}, {"timed", 1}}},
                                 {"reference", {{"spp", 4}}}};
  ASSERT_EQ(run_with_registry(config, registry, "plugin_inputs").summary.ok, 1);
  // The sphere grid's ground: y = 0, facing up towards the spheres.
  EXPECT_TRUE(seen.has_plane);
  EXPECT_NEAR(seen.plane.x, 0.0f, 1e-6f);
  EXPECT_NEAR(seen.plane.y, 1.0f, 1e-6f);
  EXPECT_NEAR(seen.plane.z, 0.0f, 1e-6f);
  EXPECT_NEAR(seen.plane.w, 0.0f, 1e-6f);
  EXPECT_EQ(seen.albedo_format, GL_RGBA8);
  EXPECT_EQ(seen.shading_normal_format, GL_RGBA32F);
}

}  // namespace
}  // namespace sb::test
