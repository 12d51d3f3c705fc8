#pragma once
// A job's frames on GL: one frame of a technique in the harness's brackets,
// the control prepared once per (scene, resolution), and the FrameTarget
// that renders a job's frame schedule (run/frame_schedule.h) with them.
#include <functional>
#include <memory>
#include <string>

#include "config/experiment.h"
#include "core/image.h"
#include "gl/pass_timer.h"
#include "plugin/technique.h"
#include "run/frame_schedule.h"
#include "run/gbuffer.h"
#include "run/injected_delay.h"
#include "run/run_events.h"

namespace sb::run {

// What every job of one (scene, resolution) draws with.
struct FrameSetup {
  FrameTargets& targets;
  const core::Scene& scene;
  const plugin::FrameInputs& in;
};

// One frame: the G-buffer's restore, the technique and shading, each in one
// harness bracket. In fine detail the technique's own passes are the
// brackets instead, and the sum of their times is what it pays for them.
// `delay`, when given, ends the frame (SHADOWBENCH_INJECT_DELAY).
gl::PassTimer::Frame render_frame(gl::PassTimer& timer, plugin::Technique& technique,
                                  const std::string& frame_name, gl::PassDetail detail,
                                  const FrameSetup& f, const InjectedDelay* delay);

// A technique's V, shaded as the reference's is: untimed.
core::ImageF shade(const FrameSetup& f, const core::ImageF& visibility);

// The control job of one (scene, resolution), prepared once: its frames are
// timed next to every job's.
struct Control {
  std::string name;
  std::unique_ptr<plugin::Technique> technique;
};

// The control, prepared and its shaders compiled before any job's frame.
// A control that fails fails the (scene, resolution)'s jobs: their times
// would have nothing to be relative to.
Control prepare_control(const config::TechniqueVariant& tv, const FrameSetup& f,
                        gl::TimingSource source);

// A job's frames and its control's, all timed by one timer. A throw in one
// of the job's own frames is the technique's, in "render"
// (run/technique_phase.h).
class TechniqueFrames : public FrameTarget {
 public:
  TechniqueFrames(const FrameSetup& f, plugin::Technique& technique, std::string technique_name,
                  Control* control, const InjectedDelay* delay, gl::TimingSource source,
                  std::function<void()> take_turn);
  gl::PassTimer::Frame job_frame(const std::string& name, gl::PassDetail detail) override;
  gl::PassTimer::Frame control_frame(const std::string& name) override;
  void take_turn() override { take_turn_(); }
  // Says each frame's phase ("render(), <frame>") to `events` before it.
  void tell_phases(RunEvents& events) { events_ = &events; }

 private:
  const FrameSetup& f_;
  plugin::Technique& technique_;
  std::string technique_name_;  // its plugin's name, for the phase's messages
  Control* control_;
  const InjectedDelay* delay_;
  gl::PassTimer timer_;
  std::function<void()> take_turn_;
  RunEvents* events_ = nullptr;
};

}  // namespace sb::run
