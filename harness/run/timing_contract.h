#pragma once
// The timing contract of a technique (plugin/technique.h), checked on one
// technique on a small scene: `shadowbench check-technique` runs these
// checks on a plugin author's technique, and tests/techniques/
// test_timing_contract.cpp on every built-in.
//
// prepare() runs once per (scene, resolution), untimed, and must not depend
// on the light or the camera: whatever it derived from either would go
// stale when that moves, and a technique that did so would be charging its
// per-frame work to the untimed prepare(). The check: technique A is
// prepared under light L1 and renders a frame; the light moves (its centre
// shifts, it turns and tilts) and A renders again. A fresh technique B,
// prepared under the moved light, renders too. A's second frame must equal
// B's to the bit: everything light-dependent happened in render(). The same
// again with the camera moved instead (a new G-buffer, view and projection,
// as a camera animated between frames would give).
//
// And every frame, as the runner draws it, writes V in [0,1] (finite) into
// every pixel (the target holds NaN before each frame here, so V left from
// prepare() or an earlier frame shows), two frames in a row are equal, and
// no frame writes the G-buffer's colour attachments, which every technique
// reads (the runner renders them once per (scene, resolution)).
//
// A temporal technique (TechniqueInfo::temporal) carries state from frame to
// frame by design, so for it "A's second frame" becomes A's first frame
// after the move (prepared under L1, nothing rendered before the move), and
// "two frames in a row are equal" becomes "two instances prepared alike
// render the same sequence of frames".
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "gl/gpu_scene.h"
#include "plugin/derived_data.h"
#include "plugin/registry.h"
#include "plugin/technique.h"
#include "run/gbuffer.h"

namespace sb::run {

// The light of the scene the checks run on.
enum class ContractLight { Square, Linear, Sun };
const char* to_string(ContractLight light);  // "square", "linear", "sun"

// The scene the checks run on: a 2×2 sphere grid over the ground, seen from
// close by, with a 2-unit square light; Linear: a 2-unit segment instead
// (for techniques that need a linear light); Sun: the sun from the square's
// direction, 2° across (for techniques that need the sun).
core::Scene contract_scene(ContractLight light = ContractLight::Square);
// The same light a little elsewhere: the centre shifted, the axis tilted and
// the rectangle turned about it, so any frustum fitted to the first light,
// and any point sampled on it, is wrong for this one.
core::AreaLight moved_light(const core::AreaLight& l);
// The camera elsewhere: to the left, higher and nearer, looking at another
// point, so that every pixel sees another surface point than before.
core::Camera moved_camera(const core::Camera& c);

size_t differing_pixels(const core::ImageF& a, const core::ImageF& b);

using TechniqueFactory = std::function<std::unique_ptr<plugin::Technique>()>;

// A scene on the GPU with its G-buffer and FrameInputs, where techniques are
// prepared and render frames as the runner draws them. Needs a current GL
// context; the CPU and GPU data of the needs of `techniques` are derived as
// the planner and the runner derive them.
class ContractStage {
 public:
  ContractStage(core::Scene scene, int width, int height,
                const std::vector<const plugin::TechniqueInfo*>& techniques,
                const plugin::Registry& plugins);

  // Puts the camera at `camera`: its G-buffer, rendered once as the runner
  // does per (scene, resolution) (frames restore it), and the inputs that
  // see it. FrameInputs points at the stage's scene: moving its light moves
  // the light the technique sees, as a light animated between frames would.
  void look_through(const core::Camera& camera);
  void set_light(const core::AreaLight& light) { scene_.light = light; }
  core::Scene& scene() { return scene_; }
  const plugin::FrameInputs& inputs() const { return in_; }
  int width() const { return targets_->width(); }
  int height() const { return targets_->height(); }
  // Why the scene cannot serve technique `i` of the constructor's list
  // ("" when it can).
  const std::string& skip_reason(size_t i) const { return skip_reason_[i]; }

  // One frame as the runner draws it: the G-buffer's restore, then the
  // technique. With `poison`, the visibility target is filled with NaN first.
  core::ImageF render(plugin::Technique& technique, bool poison = false);

  // Technique A, prepared after `to_first`, renders there and again after
  // `to_second`; technique B, prepared after `to_second`, renders there.
  // `temporal`: A renders nothing before the move, and a_first is a third
  // instance's first frame.
  struct Frames {
    core::ImageF a_first, a_moved, b_moved;
  };
  Frames across_a_move(const TechniqueFactory& create, const std::function<void()>& to_first,
                       const std::function<void()>& to_second, bool temporal = false);

  // The G-buffer's colour attachments: position, geometric normal, shading
  // normal, albedo.
  std::vector<core::ImageF> read_gbuffer() const;

 private:
  // In this order: the derived data, uploaded over the scene on the GPU,
  // goes before it.
  core::Scene scene_;
  std::unique_ptr<gl::GpuScene> gpu_;
  std::unique_ptr<FrameTargets> targets_;
  plugin::DerivedData derived_;
  std::vector<std::string> skip_reason_;
  plugin::FrameInputs in_;
};

// One check's outcome: `failure` says what went wrong ("" when it passed).
struct ContractCheck {
  std::string name;
  std::string failure;
  bool passed() const { return failure.empty(); }
};

// Moving the light (the camera) between prepare() and a frame changes
// nothing against a technique prepared after the move; `expect_change`: and
// the move changes V (not for controls, which are V = 1 anywhere);
// `temporal`: the technique's TechniqueInfo::temporal.
ContractCheck check_light_move(ContractStage& stage, const TechniqueFactory& create,
                               bool expect_change, bool temporal = false);
ContractCheck check_camera_move(ContractStage& stage, const TechniqueFactory& create,
                                bool expect_change, bool temporal = false);
// Two frames leave the G-buffer's colour attachments as they were.
ContractCheck check_gbuffer_untouched(ContractStage& stage, const TechniqueFactory& create);
// Each of three frames writes V, finite and in [0,1], into every pixel.
ContractCheck check_visibility_written(ContractStage& stage, const TechniqueFactory& create);
// Three frames in a row, nothing moved between them, are equal; `temporal`:
// two instances' first three frames are equal, frame by frame.
ContractCheck check_deterministic(ContractStage& stage, const TechniqueFactory& create,
                                  bool temporal = false);

// All of the above, in that order; a check whose technique throws fails
// with the exception's message.
std::vector<ContractCheck> check_timing_contract(ContractStage& stage,
                                                 const TechniqueFactory& create, bool expect_change,
                                                 bool temporal = false);

}  // namespace sb::run
