#pragma once
// One job on GL: prepare the technique, render and time its frame schedule
// (run/frame_schedule.h) next to the control's, check and measure its V
// against its measurement basis (run/measurement_basis.h), write its images
// and, with the "stability" block, its stability figures.
#include <cstdint>
#include <map>
#include <string>

#include "config/experiment.h"
#include "gl/pass_timer.h"
#include "record/job_record.h"
#include "record/phases_record.h"
#include "run/injected_delay.h"
#include "run/measurement_basis.h"
#include "run/run_events.h"
#include "run/runner.h"
#include "run/stability_probe.h"
#include "run/technique_frames.h"

namespace sb::run {

// What every job of one (scene, resolution) runs with.
struct JobSetting {
  const config::Experiment& e;
  const RunOptions& o;
  RunEvents& events;
  gl::TimingSource timing_source;
  const InjectedDelay* injected_delay = nullptr;  // SHADOWBENCH_INJECT_DELAY, for any job
  const FrameSetup& frame;
  const MeasurementBasis& basis;
  Control* control = nullptr;
  StabilityProbe* stability = nullptr;
};

// Whatever the job got to stays in `r` and `phases` when it throws.
// `need_gpu_bytes`: what the harness holds on the GPU for the technique's
// needs (UploadedScene::gpu_bytes_held_for), charged beside its own storage.
// `time_only` (run --retime): prepared and timed as any job, then nothing
// is read back, measured or written; `s.basis` may be empty.
void run_job(const JobSetting& s, const config::TechniqueVariant& tv,
             const std::map<std::string, std::int64_t>& need_gpu_bytes, record::JobRecord& r,
             record::PhasesRecord& phases, bool time_only = false);

}  // namespace sb::run
