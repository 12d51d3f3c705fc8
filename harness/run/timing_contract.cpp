#include "run/timing_contract.h"

#include <exception>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <utility>

#include "core/scene_types.h"
#include "gl/context.h"
#include "gl/debug.h"
#include "gl/pass_timer.h"
#include "metrics/job_metrics.h"
#include "plan/need_resolution.h"
#include "scenes/need_providers.h"
#include "scenes/receiver_inference.h"

namespace sb::run {

using core::AreaLight;
using core::Camera;
using core::ImageF;
using core::Mesh;
using core::Scene;
using core::SceneType;
using gl::MeshDrawFlags;
using plugin::NeedProvider;
using plugin::PlanarReceiver;
using plugin::Technique;
using plugin::TechniqueInfo;

const char* to_string(ContractLight light) {
  switch (light) {
    case ContractLight::Square:
      return "square";
    case ContractLight::Linear:
      return "linear";
    case ContractLight::Sun:
      return "sun";
  }
  return "?";
}

Scene contract_scene(ContractLight light) {
  const SceneType* type = core::find_scene_type("sphere_grid");
  Scene s =
      type->build(core::resolve_params(type->params, {{"grid", 2}, {"light_size", 2.0}}, "", ""));
  s.camera.eye = {0.0f, 3.0f, 4.5f};
  s.camera.target = {0.0f, 0.6f, 0.0f};
  if (light == ContractLight::Linear)
    s.light = core::make_area_light(s.light.center, s.light.target, s.light.width(), 0.0f,
                                    s.light.intensity);
  if (light == ContractLight::Sun)
    s.light = core::make_sun_light(s.light.to_sun(), s.light.target, glm::radians(2.0f),
                                   glm::length(s.light.center - s.light.target), s.light.intensity);
  return s;
}

AreaLight moved_light(const AreaLight& l) {
  // The sun turns (by about 15°) and looks elsewhere.
  if (l.is_sun()) {
    const glm::vec3 target = l.target + glm::vec3(-0.3f, 0.0f, 0.4f);
    return core::make_sun_light(l.to_sun() + glm::vec3(0.2f, 0.0f, -0.15f), target,
                                l.angular_diameter, glm::length(l.center - l.target), l.intensity);
  }
  AreaLight m = core::make_area_light(l.center + glm::vec3(1.0f, -0.5f, 0.8f),
                                      l.target + glm::vec3(-0.3f, 0.0f, 0.4f), l.width(),
                                      l.height(), l.intensity);
  const glm::quat turn = glm::angleAxis(glm::radians(12.0f), m.direction());
  m.half_u = turn * m.half_u;
  m.half_v = turn * m.half_v;
  return m;
}

Camera moved_camera(const Camera& c) {
  Camera m = c;
  m.eye = c.eye + glm::vec3(-1.6f, 0.7f, -0.9f);
  m.target = c.target + glm::vec3(0.4f, -0.3f, -0.2f);
  return m;
}

size_t differing_pixels(const ImageF& a, const ImageF& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.data.size(); ++i) n += a.data[i] != b.data[i] ? 1 : 0;
  return n;
}

ContractStage::ContractStage(Scene scene, int width, int height,
                             const std::vector<const TechniqueInfo*>& techniques,
                             const plugin::Registry& plugins)
    : scene_(std::move(scene)) {
  std::vector<std::vector<uint32_t>> adjacency(scene_.meshes.size());
  std::vector<MeshDrawFlags> flags(scene_.meshes.size());
  for (size_t i = 0; i < scene_.meshes.size(); ++i) {
    const Mesh& m = scene_.meshes[i];
    if (m.casts_shadow) adjacency[i] = build_adjacency_indices(m);
    flags[i].closed = m.casts_shadow && analyse_topology(m).closed();
    flags[i].nothing_behind = !m.casts_shadow && can_shadow_nothing(scene_, i);
  }
  gpu_ = std::make_unique<gl::GpuScene>(scene_, adjacency, flags);
  targets_ = std::make_unique<FrameTargets>(width, height);
  // The CPU data the techniques' needs ask for, as the planner derives it
  // for a run, and their GPU stages, as the runner does.
  plan::ResolvedNeeds needs = plan::resolve_needs(scene_, techniques, &plugins, plan::Derive::All);
  derived_ = std::move(needs.data);
  skip_reason_ = std::move(needs.skip_reason);
  for (const NeedProvider* p : needs.uploads) p->upload(scene_, *gpu_, derived_);
  look_through(scene_.camera);
}

void ContractStage::look_through(const Camera& camera) {
  scene_.camera = camera;
  const glm::mat4 view = camera.view();
  const glm::mat4 projection = camera.projection(float(width()) / float(height()));
  gl::reset_state();
  targets_->render_gbuffer(*gpu_, projection * view);
  gl::reset_state();
  in_ = targets_->inputs(scene_, *gpu_, view, projection);
  PlanarReceiver receiver;
  in_.has_receiver_plane = find_planar_receiver(scene_, receiver);
  in_.receiver_plane = receiver.plane;
  in_.derived = &derived_;
}

ImageF ContractStage::render(Technique& technique, bool poison) {
  if (poison)
    targets_->upload_visibility(
        ImageF(width(), height(), 1, std::numeric_limits<float>::quiet_NaN()));
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

ContractStage::Frames ContractStage::across_a_move(const TechniqueFactory& create,
                                                   const std::function<void()>& to_first,
                                                   const std::function<void()>& to_second,
                                                   bool temporal) {
  Frames f;
  to_first();
  const std::unique_ptr<Technique> a = create();
  a->prepare(in_);
  if (temporal) {
    const std::unique_ptr<Technique> first = create();
    first->prepare(in_);
    f.a_first = render(*first);
  } else {
    f.a_first = render(*a);
  }
  to_second();
  f.a_moved = render(*a);
  const std::unique_ptr<Technique> b = create();
  b->prepare(in_);
  f.b_moved = render(*b);
  return f;
}

std::vector<ImageF> ContractStage::read_gbuffer() const {
  return {read_texture(in_.gbuffer_position, width(), height(), 4),
          read_texture(in_.gbuffer_normal, width(), height(), 4),
          read_texture(in_.gbuffer_shading_normal, width(), height(), 4),
          read_texture(in_.gbuffer_albedo, width(), height(), 4)};
}

namespace {

// `check` run with its name; what it throws fails it.
ContractCheck run_check(const std::string& name, const std::function<std::string()>& check) {
  try {
    return {name, check()};
  } catch (const std::exception& e) {
    return {name, std::string("threw: ") + e.what()};
  }
}

// A's second frame equals B's; and moving made a difference, else that
// proves nothing.
std::string prepare_kept_nothing_that_moved(const ContractStage::Frames& f, bool expect_change,
                                            const std::string& what) {
  if (!f.a_moved.same_shape(f.b_moved)) return "the frames differ in size";
  if (const size_t n = differing_pixels(f.a_moved, f.b_moved); n > 0)
    return "prepared under the first " + what + ", then rendered under the second, " +
           std::to_string(n) + " pixels differ from the same technique prepared under the " +
           "second " + what + ": prepare() keeps something that depends on the " + what +
           " (do that work in render())";
  const size_t changed = differing_pixels(f.a_first, f.b_moved);
  if (expect_change && changed <= f.a_first.pixel_count() / 100)
    return "moving the " + what + " changed only " + std::to_string(changed) +
           " pixels of V: does render() draw with the " + what + " it is given?";
  return "";
}

}  // namespace

ContractCheck check_light_move(ContractStage& stage, const TechniqueFactory& create,
                               bool expect_change, bool temporal) {
  return run_check("prepare() keeps nothing of the light (moved after it)", [&] {
    const AreaLight first = stage.scene().light, second = moved_light(first);
    std::string failure;
    try {
      const auto f = stage.across_a_move(
          create, [&] { stage.set_light(first); }, [&] { stage.set_light(second); }, temporal);
      failure = prepare_kept_nothing_that_moved(f, expect_change, "light");
    } catch (...) {
      stage.set_light(first);
      throw;
    }
    stage.set_light(first);
    return failure;
  });
}

ContractCheck check_camera_move(ContractStage& stage, const TechniqueFactory& create,
                                bool expect_change, bool temporal) {
  return run_check("prepare() keeps nothing of the camera (moved after it)", [&] {
    const Camera first = stage.scene().camera, second = moved_camera(first);
    std::string failure;
    try {
      const auto f = stage.across_a_move(
          create, [&] { stage.look_through(first); }, [&] { stage.look_through(second); },
          temporal);
      failure = prepare_kept_nothing_that_moved(f, expect_change, "camera");
    } catch (...) {
      stage.look_through(first);
      throw;
    }
    stage.look_through(first);
    return failure;
  });
}

ContractCheck check_gbuffer_untouched(ContractStage& stage, const TechniqueFactory& create) {
  return run_check("frames leave the G-buffer's colour attachments alone", [&] {
    const std::vector<ImageF> before = stage.read_gbuffer();
    const std::unique_ptr<Technique> t = create();
    t->prepare(stage.inputs());
    stage.render(*t);
    stage.render(*t);
    const std::vector<ImageF> after = stage.read_gbuffer();
    const char* const names[] = {"position", "geometric normal", "shading normal", "albedo"};
    for (size_t k = 0; k < before.size(); ++k)
      if (const size_t n = differing_pixels(before[k], after[k]); n > 0)
        return "a frame changed " + std::to_string(n) + " pixels of the G-buffer's " + names[k] +
               " attachment, which every technique reads";
    return std::string();
  });
}

ContractCheck check_visibility_written(ContractStage& stage, const TechniqueFactory& create) {
  return run_check("every frame writes V in [0,1] into every pixel", [&] {
    const std::unique_ptr<Technique> t = create();
    t->prepare(stage.inputs());
    for (int frame = 1; frame <= 3; ++frame) {
      const record::VisibilityCheckRecord c = metrics::check_visibility(stage.render(*t, true));
      if (c.nonfinite + c.below_0 + c.above_1 > 0)
        return "frame " + std::to_string(frame) + ": " + std::to_string(c.nonfinite) +
               " pixels NaN/Inf, " + std::to_string(c.below_0) + " below 0, " +
               std::to_string(c.above_1) + " above 1 of " +
               std::to_string(size_t(stage.width()) * size_t(stage.height())) +
               " (the target held NaN before the frame: render() must write V into every "
               "pixel, in every frame)";
    }
    return std::string();
  });
}

ContractCheck check_deterministic(ContractStage& stage, const TechniqueFactory& create,
                                  bool temporal) {
  if (temporal)
    return run_check("frames are deterministic (two instances render the same three frames)", [&] {
      const std::unique_ptr<Technique> a = create(), b = create();
      a->prepare(stage.inputs());
      b->prepare(stage.inputs());
      std::vector<ImageF> frames;
      for (int frame = 1; frame <= 3; ++frame) frames.push_back(stage.render(*a));
      for (int frame = 1; frame <= 3; ++frame)
        if (const size_t n = differing_pixels(frames[size_t(frame - 1)], stage.render(*b)); n > 0)
          return "frame " + std::to_string(frame) + " of a second instance differs from the " +
                 "first's in " + std::to_string(n) + " pixels, with nothing moved";
      return std::string();
    });
  return run_check("frames are deterministic (three in a row are equal)", [&] {
    const std::unique_ptr<Technique> t = create();
    t->prepare(stage.inputs());
    const ImageF first = stage.render(*t);
    for (int frame = 2; frame <= 3; ++frame)
      if (const size_t n = differing_pixels(first, stage.render(*t)); n > 0)
        return "frame " + std::to_string(frame) + " differs from frame 1 in " + std::to_string(n) +
               " pixels, with nothing moved";
    return std::string();
  });
}

std::vector<ContractCheck> check_timing_contract(ContractStage& stage,
                                                 const TechniqueFactory& create, bool expect_change,
                                                 bool temporal) {
  return {check_light_move(stage, create, expect_change, temporal),
          check_camera_move(stage, create, expect_change, temporal),
          check_visibility_written(stage, create), check_deterministic(stage, create, temporal),
          check_gbuffer_untouched(stage, create)};
}

}  // namespace sb::run
