// The timing contract of Technique::prepare() (plugin/technique.h): it runs
// once per (scene, resolution), untimed, and must not depend on the light or
// the camera. Whatever it derived from either would go stale when that
// moves, and a technique that did so would be charging its per-frame work to
// the untimed prepare().
//
// The check, for every technique the plugins register (default parameters)
// and the technique variants of configs/quick.json: technique A is prepared
// under light L1 and renders a frame; the light moves (its centre shifts,
// it turns and tilts) and A renders again. A fresh technique B, prepared
// under the moved light, renders too. A's second frame must equal B's to
// the bit: everything light-dependent happened in render(). The same again
// with the camera moved instead of the light (a new G-buffer, view and
// projection, as a camera animated between frames would give).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <glm/gtc/quaternion.hpp>
#include <memory>
#include <string>
#include <vector>

#include "config/experiment.h"
#include "gl/context.h"
#include "gl/debug.h"
#include "gl/gpu_scene.h"
#include "gl/objects.h"
#include "gl/pass_timer.h"
#include "plan/need_resolution.h"
#include "plugin/registry.h"
#include "run/gbuffer.h"
#include "scenes/need_providers.h"
#include "scenes/receiver_inference.h"

namespace sb::test {

using config::Experiment;
using config::load_experiment;
using config::parse_experiment;
using config::TechniqueVariant;
using core::AreaLight;
using core::Camera;
using core::find_scene_type;
using core::ImageF;
using core::make_area_light;
using core::Mesh;
using core::Params;
using core::resolve_params;
using core::Scene;
using core::SceneType;
using gl::GpuScene;
using gl::MeshDrawFlags;
using plan::Derive;
using plan::resolve_needs;
using plan::ResolvedNeeds;
using plugin::DerivedData;
using plugin::FrameInputs;
using plugin::NeedProvider;
using plugin::PlanarReceiver;
using plugin::Registry;
using plugin::Technique;
using plugin::TechniqueInfo;
using run::FrameTargets;
using run::read_texture;

namespace {

constexpr int kWidth = 96;
constexpr int kHeight = 72;

// Every registered technique with its defaults, some modes, then quick.json's variants.
std::vector<TechniqueVariant> variants_under_test(const Registry& plugins) {
  nlohmann::json names = nlohmann::json::array();
  for (const TechniqueInfo& t : plugins.all()) names.push_back(t.name);
  const nlohmann::json defaults = {{"name", "defaults"},
                                   {"scenes", {{{"type", "sphere_grid"}}}},
                                   {"techniques", names},
                                   {"resolutions", {{kWidth, kHeight}}}};
  std::vector<TechniqueVariant> out = parse_experiment(defaults, "<defaults>", plugins).techniques;
  // Modes that draw passes of their own, which neither the defaults nor
  // quick.json reach.
  const nlohmann::json modes = {
      {"name", "modes"},
      {"scenes", {{{"type", "sphere_grid"}}}},
      {"techniques",
       {{{"name", "blurred_visibility"}, {"params", {{"space", "light"}}}},
        {{"name", "two_map_bound"}, {"params", {{"shade", {"gradient", "midpoint"}}}}}}},
      {"resolutions", {{kWidth, kHeight}}}};
  const auto extra = parse_experiment(modes, "<modes>", plugins).techniques;
  out.insert(out.end(), extra.begin(), extra.end());
  const Experiment quick =
      load_experiment(std::string(SHADOWBENCH_SOURCE_DIR) + "/configs/quick.json", plugins);
  out.insert(out.end(), quick.techniques.begin(), quick.techniques.end());
  return out;
}

// A small sphere grid seen from close by: 2×2 spheres over the ground.
Scene small_scene() {
  const SceneType* type = find_scene_type("sphere_grid");
  Scene s = type->build(resolve_params(type->params, {{"grid", 2}, {"light_size", 2.0}}, "", ""));
  s.camera.eye = {0.0f, 3.0f, 4.5f};
  s.camera.target = {0.0f, 0.6f, 0.0f};
  return s;
}

// The same light a little elsewhere: the centre shifted, the axis tilted and
// the rectangle turned about it, so any frustum fitted to the first light,
// and any point sampled on it, is wrong for this one.
AreaLight moved(const AreaLight& l) {
  AreaLight m =
      make_area_light(l.center + glm::vec3(1.0f, -0.5f, 0.8f),
                      l.target + glm::vec3(-0.3f, 0.0f, 0.4f), l.width(), l.height(), l.intensity);
  const glm::quat turn = glm::angleAxis(glm::radians(12.0f), m.direction());
  m.half_u = turn * m.half_u;
  m.half_v = turn * m.half_v;
  return m;
}

// The camera elsewhere: to the left, higher and nearer, looking at another
// point, so that every pixel sees another surface point than before.
Camera moved(const Camera& c) {
  Camera m = c;
  m.eye = c.eye + glm::vec3(-1.6f, 0.7f, -0.9f);
  m.target = c.target + glm::vec3(0.4f, -0.3f, -0.2f);
  return m;
}

// A plausible breach of the contract: it keeps the camera's matrices from
// prepare() and hands them to the technique it wraps every frame, as a
// technique that set its camera uniforms once in prepare() would.
class StaleCamera final : public Technique {
 public:
  explicit StaleCamera(std::unique_ptr<Technique> inner) : inner_(std::move(inner)) {}
  void prepare(const FrameInputs& in) override {
    inner_->prepare(in);
    prepared_ = in;
  }
  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    FrameInputs stale = in;
    stale.view = prepared_.view;
    stale.projection = prepared_.projection;
    stale.view_projection = prepared_.view_projection;
    inner_->render(stale, timer);
  }

 private:
  std::unique_ptr<Technique> inner_;
  FrameInputs prepared_;
};

class TimingContract : public ::testing::Test {
 protected:
  void SetUp() override {
    plugins_.load_plugins(SHADOWBENCH_PLUGIN_DIR);
    context_ = gl::create_context(gl::Backend::OSMesa);
    scene_ = small_scene();
    first_light_ = scene_.light;
    std::vector<std::vector<uint32_t>> adjacency(scene_.meshes.size());
    std::vector<MeshDrawFlags> flags(scene_.meshes.size());
    for (size_t i = 0; i < scene_.meshes.size(); ++i) {
      const Mesh& m = scene_.meshes[i];
      if (m.casts_shadow) adjacency[i] = build_adjacency_indices(m);
      flags[i].closed = m.casts_shadow && analyse_topology(m).closed();
      flags[i].nothing_behind = !m.casts_shadow && can_shadow_nothing(scene_, i);
    }
    gpu_ = std::make_unique<GpuScene>(scene_, adjacency, flags);
    targets_ = std::make_unique<FrameTargets>(kWidth, kHeight);
    // The CPU data every technique's needs ask for (the caster edges of the
    // CPU silhouettes), as the planner derives it for a run.
    std::vector<const TechniqueInfo*> all;
    for (const TechniqueInfo& t : plugins_.all()) all.push_back(&t);
    ResolvedNeeds needs = resolve_needs(scene_, all, &plugins_, Derive::All);
    derived_ = std::move(needs.data);
    // And their GPU stages (the silhouette edges' buffer), as the runner does.
    for (const NeedProvider* p : needs.uploads) p->upload(scene_, *gpu_, derived_);
    look_through(scene_.camera);
  }

  // Puts the camera at `camera`: its G-buffer, rendered once as the runner
  // does per (scene, resolution) (frames restore it), and the inputs that
  // see it. FrameInputs points at scene_: moving scene_.light moves the light
  // the technique sees, as a light animated between frames would.
  void look_through(const Camera& camera) {
    scene_.camera = camera;
    const glm::mat4 view = camera.view();
    const glm::mat4 projection = camera.projection(float(kWidth) / float(kHeight));
    view_projection_ = projection * view;
    gl::reset_state();
    targets_->render_gbuffer(*gpu_, view_projection_);
    gl::reset_state();
    in_ = targets_->inputs(scene_, *gpu_, view, projection);
    PlanarReceiver receiver;
    in_.has_receiver_plane = find_planar_receiver(scene_, receiver);
    in_.receiver_plane = receiver.plane;
    in_.derived = &derived_;
  }

  // One frame as the runner draws it: the G-buffer's restore, then the technique.
  ImageF render(Technique& technique) {
    gl::reset_state();
    targets_->restore_gbuffer();
    gl::reset_state();
    gl::PassTimer timer(gl::TimingSource::CpuFinish, gl::PassDetail::Coarse);
    timer.begin_frame();
    {
      auto bracket = timer.bracket("technique");
      technique.render(in_, timer);
    }
    timer.end_frame();
    gl::throw_if_errors("timing contract frame");
    gl::reset_state();
    return targets_->read_visibility();
  }

  // Technique A, prepared after `to_first`, renders there and again after
  // `to_second`; technique B, prepared after `to_second`, renders there.
  struct Frames {
    ImageF a_first, a_moved, b_moved;
  };
  Frames across_a_move(const std::function<std::unique_ptr<Technique>()>& create,
                       const std::function<void()>& to_first,
                       const std::function<void()>& to_second) {
    Frames f;
    to_first();
    const std::unique_ptr<Technique> a = create();
    a->prepare(in_);
    f.a_first = render(*a);
    to_second();
    f.a_moved = render(*a);
    const std::unique_ptr<Technique> b = create();
    b->prepare(in_);
    f.b_moved = render(*b);
    return f;
  }

  Registry plugins_;
  std::unique_ptr<gl::Context> context_;
  Scene scene_;
  AreaLight first_light_;
  std::unique_ptr<GpuScene> gpu_;
  std::unique_ptr<FrameTargets> targets_;
  glm::mat4 view_projection_{1.0f};
  DerivedData derived_;
  FrameInputs in_;
};

size_t differing_pixels(const ImageF& a, const ImageF& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.data.size(); ++i) n += a.data[i] != b.data[i] ? 1 : 0;
  return n;
}

// A's second frame equals B's; and moving made a difference, else that
// proves nothing (`none` and the controls are V = 1 anywhere).
void expect_prepare_kept_nothing_that_moved(const TechniqueVariant& tv, const ImageF& a_first,
                                            const ImageF& a_moved, const ImageF& b_moved,
                                            const std::string& what) {
  ASSERT_TRUE(a_moved.same_shape(b_moved));
  EXPECT_EQ(differing_pixels(a_moved, b_moved), 0u)
      << "prepared under the first " << what << ", then rendered under the second, " << tv.name
      << " differs from the same technique prepared under the second " << what;
  if (tv.info->name != "none" && tv.info->family != "control") {
    EXPECT_GT(differing_pixels(a_first, b_moved), size_t(kWidth * kHeight / 100))
        << "moving the " << what << " hardly changed " << tv.name << "'s visibility";
  }
}

TEST_F(TimingContract, AfterTheLightMovesAFrameEqualsOnePreparedUnderTheMovedLight) {
  const std::vector<TechniqueVariant> variants = variants_under_test(plugins_);
  ASSERT_GE(variants.size(), plugins_.all().size());
  const AreaLight second_light = moved(first_light_);
  for (const TechniqueVariant& tv : variants) {
    SCOPED_TRACE(tv.name);
    const Frames f =
        across_a_move([&] { return tv.info->create(tv.params); },
                      [&] { scene_.light = first_light_; }, [&] { scene_.light = second_light; });
    expect_prepare_kept_nothing_that_moved(tv, f.a_first, f.a_moved, f.b_moved, "light");
  }
}

TEST_F(TimingContract, AfterTheCameraMovesAFrameEqualsOnePreparedUnderTheMovedCamera) {
  const std::vector<TechniqueVariant> variants = variants_under_test(plugins_);
  ASSERT_GE(variants.size(), plugins_.all().size());
  const Camera first_camera = scene_.camera, second_camera = moved(first_camera);
  for (const TechniqueVariant& tv : variants) {
    SCOPED_TRACE(tv.name);
    const Frames f =
        across_a_move([&] { return tv.info->create(tv.params); },
                      [&] { look_through(first_camera); }, [&] { look_through(second_camera); });
    expect_prepare_kept_nothing_that_moved(tv, f.a_first, f.a_moved, f.b_moved, "camera");
  }
}

// The check above catches a technique that keeps the camera from prepare():
// shadow_volume, handed the first camera's matrices over the second camera's
// G-buffer, draws its volumes where the first camera saw them.
TEST_F(TimingContract, TheCameraCheckCatchesATechniqueThatKeepsTheCameraFromPrepare) {
  const TechniqueInfo* volume = plugins_.find("shadow_volume");
  ASSERT_NE(volume, nullptr);
  const Params defaults = resolve_params(volume->params, nlohmann::json::object(), "", "");
  const Camera first_camera = scene_.camera, second_camera = moved(first_camera);
  const Frames f =
      across_a_move([&] { return std::make_unique<StaleCamera>(volume->create(defaults)); },
                    [&] { look_through(first_camera); }, [&] { look_through(second_camera); });
  EXPECT_GT(differing_pixels(f.a_moved, f.b_moved), size_t(kWidth * kHeight / 100));
}

// The runner renders the G-buffer once per (scene, resolution) and restores
// only its depth-stencil between frames (run/gbuffer.h): that is fair only
// if no technique writes the colour attachments every technique reads.
TEST_F(TimingContract, NoTechniqueWritesTheGBufferColourAttachments) {
  const auto gbuffer = [&] {
    return std::vector<ImageF>{read_texture(in_.gbuffer_position, kWidth, kHeight, 4),
                               read_texture(in_.gbuffer_normal, kWidth, kHeight, 4),
                               read_texture(in_.gbuffer_shading_normal, kWidth, kHeight, 4),
                               read_texture(in_.gbuffer_albedo, kWidth, kHeight, 4)};
  };
  const std::vector<ImageF> before = gbuffer();
  size_t covered = 0;
  for (size_t i = 0; i < before[0].pixel_count(); ++i) covered += before[0].data[i * 4 + 3] > 0.5f;
  ASSERT_GT(covered, size_t(kWidth * kHeight / 4)) << "the G-buffer shows too little of the scene";
  const char* const names[] = {"position", "geometric normal", "shading normal", "albedo"};
  for (const TechniqueVariant& tv : variants_under_test(plugins_)) {
    SCOPED_TRACE(tv.name);
    const std::unique_ptr<Technique> t = tv.info->create(tv.params);
    t->prepare(in_);
    render(*t);
    render(*t);
    const std::vector<ImageF> after = gbuffer();
    for (size_t k = 0; k < before.size(); ++k)
      EXPECT_EQ(differing_pixels(before[k], after[k]), 0u)
          << tv.name << " changed the G-buffer's " << names[k] << " attachment";
  }
}

std::vector<uint32_t> read_depth_stencil(GLuint texture) {
  std::vector<uint32_t> out(size_t(kWidth) * kHeight);
  glGetTextureImage(texture, 0, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8,
                    GLsizei(out.size() * sizeof(uint32_t)), out.data());
  gl::throw_if_errors("reading the depth-stencil");
  return out;
}

// What stencil techniques leave in the shared depth-stencil (counts, a
// cleared depth) is gone when the next frame starts.
TEST_F(TimingContract, RestoringTheGBufferUndoesAFramesDepthStencilWrites) {
  const std::vector<uint32_t> pristine = read_depth_stencil(in_.depth_stencil);
  size_t nearer = 0;  // geometry in front of the far plane
  for (uint32_t v : pristine) nearer += (v >> 8) < 0xffffffu ? 1 : 0;
  ASSERT_GT(nearer, size_t(kWidth * kHeight / 4));
  glBindFramebuffer(GL_FRAMEBUFFER, in_.visibility_framebuffer);
  glClearNamedFramebufferfi(in_.visibility_framebuffer, GL_DEPTH_STENCIL, 0, 0.25f, 7);
  const std::vector<uint32_t> written = read_depth_stencil(in_.depth_stencil);
  ASSERT_NE(written, pristine) << "the clear did not reach the depth-stencil";
  targets_->restore_gbuffer();
  EXPECT_EQ(read_depth_stencil(in_.depth_stencil), pristine);
}

}  // namespace
}  // namespace sb::test
