#include "run/technique_frames.h"

#include <chrono>
#include <utility>

#include "gl/debug.h"
#include "gl/gl.h"
#include "gl/objects.h"
#include "run/technique_phase.h"

namespace sb::run {

using config::TechniqueVariant;
using core::ImageF;
using plugin::Technique;

gl::PassTimer::Frame render_frame(gl::PassTimer& timer, Technique& technique,
                                  const std::string& frame_name, gl::PassDetail detail,
                                  const FrameSetup& f, const InjectedDelay* delay) {
  timer.set_detail(detail);
  gl::reset_state();  // whatever a technique left behind
  const auto started = std::chrono::steady_clock::now();
  timer.begin_frame();
  {
    // The G-buffer was rendered once for the (scene, resolution); the frame
    // starts from its depth-stencil (run/gbuffer.h).
    auto p = timer.bracket("shared:gbuffer");
    f.targets.restore_gbuffer();
  }
  gl::reset_state();
  if (detail == gl::PassDetail::Coarse) {
    auto p = timer.bracket("technique");
    technique.render(f.in, timer);
  } else {
    technique.render(f.in, timer);
  }
  gl::throw_if_errors(frame_name);
  gl::reset_state();
  {
    auto p = timer.bracket("shared:shading");
    f.targets.render_shading(f.scene);
  }
  if (delay != nullptr) {
    // At the frame's end, so that a relative delay knows the frame's time;
    // a bracket of the job's own, so it counts in its technique time too.
    glFinish();
    const double so_far =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started)
            .count();
    auto p = timer.bracket("injected delay");
    delay->wait(so_far);
  }
  auto frame = timer.end_frame();
  gl::throw_if_errors(frame_name);
  return frame;
}

ImageF shade(const FrameSetup& f, const ImageF& visibility) {
  f.targets.upload_visibility(visibility);
  f.targets.render_shading(f.scene);
  return f.targets.read_shaded();
}

Control prepare_control(const TechniqueVariant& tv, const FrameSetup& f, gl::TimingSource source) {
  Control c{tv.name, tv.info->create(tv.params)};
  gl::take_debug_errors();
  c.technique->prepare(f.in);
  gl::throw_if_errors("control " + tv.name + " prepare");
  gl::PassTimer timer(source);
  render_frame(timer, *c.technique, "control " + tv.name + " compile frame", gl::PassDetail::Coarse,
               f, nullptr);
  gl::reset_state();
  return c;
}

TechniqueFrames::TechniqueFrames(const FrameSetup& f, Technique& technique,
                                 std::string technique_name, Control* control,
                                 const InjectedDelay* delay, gl::TimingSource source,
                                 std::function<void()> take_turn)
    : f_(f),
      technique_(technique),
      technique_name_(std::move(technique_name)),
      control_(control),
      delay_(delay),
      timer_(source),
      take_turn_(std::move(take_turn)) {}

gl::PassTimer::Frame TechniqueFrames::job_frame(const std::string& name, gl::PassDetail detail) {
  if (events_ != nullptr) events_->job_phase("render(), " + name);
  return in_technique_phase(technique_name_, "render", [&] {
    return render_frame(timer_, technique_, name, detail, f_, delay_);
  });
}

gl::PassTimer::Frame TechniqueFrames::control_frame(const std::string& name) {
  if (events_ != nullptr) events_->job_phase("the control's render(), " + name);
  return render_frame(timer_, *control_->technique, name, gl::PassDetail::Coarse, f_, nullptr);
}

}  // namespace sb::run
