#include "run/job_run.h"

#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <chrono>
#include <memory>
#include <utility>

#include "core/error.h"
#include "gl/allocation_meter.h"
#include "gl/debug.h"
#include "gl/gl.h"
#include "metrics/job_metrics.h"
#include "metrics/shadow_classes.h"
#include "run/frame_schedule.h"
#include "run/host_info.h"
#include "run/run_images.h"
#include "run/technique_frames.h"
#include "run/technique_phase.h"

namespace sb::run {

using config::TechniqueVariant;
using core::ImageF;
using core::JobError;
using plugin::Technique;
using record::ClassesRecord;
using record::JobRecord;
using record::PhasesRecord;
using record::SecondReferenceRecord;
using record::VisibilityCheckRecord;

namespace {

// Seconds since it was made or since the last call (record/phases_record.h).
class Lap {
 public:
  double seconds() {
    const auto now = std::chrono::steady_clock::now();
    const double out = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return out;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// Work on another TBB task, waited for before the scope it reads ends: on
// the way out of an exception too, where the task's own error is dropped
// for the one already thrown.
class TaskAside {
 public:
  template <class F>
  void run(F&& f) {
    group_.run(std::forward<F>(f));
  }
  void wait() { group_.wait(); }  // rethrows the task's exception
  TaskAside() = default;
  TaskAside(const TaskAside&) = delete;
  TaskAside& operator=(const TaskAside&) = delete;
  ~TaskAside() {
    try {
      group_.wait();
    } catch (...) {  // NOLINT(bugprone-empty-catch): the scope's own exception wins
    }
  }

 private:
  tbb::task_group group_;
};

FrameSchedule schedule_of(const JobSetting& s, const TechniqueVariant& tv) {
  FrameSchedule schedule;
  schedule.job = tv.name;
  schedule.warmup_frames = s.e.warmup_frames;
  schedule.timed_frames = s.e.timed_frames;
  if (s.control != nullptr) schedule.control = s.control->name;
  schedule.pass_detail = s.o.pass_detail;
  schedule.turn_block_frames = s.o.take_turn ? s.o.turn_block_frames : 0;
  schedule.noise_threshold = s.e.noise_threshold;
  schedule.load_average = one_minute_load_average;
  schedule.usable_cores = usable_cpus();
  // Two builds taking turns (compare-builds) must take the same turns: they
  // time a fixed auto_block frames each.
  if (s.e.timed_auto && !s.o.take_turn)
    schedule.auto_frames =
        FrameSchedule::AutoFrames{s.e.auto_target, s.e.auto_max_frames, s.e.auto_max_seconds};
  return schedule;
}

}  // namespace

void run_job(const JobSetting& s, const TechniqueVariant& tv,
             const std::map<std::string, std::int64_t>& need_gpu_bytes, JobRecord& r,
             PhasesRecord& phases, bool time_only) {
  Lap lap;
  gl::take_debug_errors();
  const std::string& who = tv.info->name;
  // Counts what the technique allocates from here to its last frame; what
  // the harness holds for its needs was made before, and is added to it.
  gl::AllocationWindow allocations;
  std::unique_ptr<Technique> technique = in_technique_phase(who, "prepare", [&] {
    s.events.job_phase("create() (the plugin's constructor)");
    std::unique_ptr<Technique> t = tv.info->create(tv.params);
    s.events.job_phase("prepare()");
    t->prepare(s.frame.in);
    gl::throw_if_errors(tv.name + " prepare");
    glFinish();  // prepare's GL work in prepare's time, not the first frame's
    return t;
  });
  phases.prepare = lap.seconds();
  // The parent stores the record before this one while prepare runs; no
  // write of its overlaps a frame (docs/robustness.md). Its wait is
  // overhead, in no phase.
  s.events.await_listener();
  lap.seconds();

  const InjectedDelay* delay = s.injected_delay != nullptr && s.injected_delay->applies_to(tv.name)
                                   ? s.injected_delay
                                   : nullptr;
  TechniqueFrames frames(s.frame, *technique, who, s.control, delay, s.timing_source,
                         [&] { s.o.take_turn(tv.name); });
  frames.tell_phases(s.events);
  r.timing = time_frames(frames, schedule_of(s, tv));
  r.technique.set_gpu_bytes(allocations.peak_bytes(), need_gpu_bytes);
  if (delay != nullptr) r.warnings.push_back(delay->describe());
  if (time_only) {
    phases.frames = lap.seconds();
    return;
  }
  // A temporal technique's last frame depends on how many came before it,
  // which the timing decided: its V is measured on a fixed frame of a fresh
  // instance instead, untimed, as the job's frames are drawn.
  if (tv.info->temporal) {
    technique.reset();
    technique = in_technique_phase(who, "prepare", [&] {
      s.events.job_phase("prepare() again, for the measured frames");
      std::unique_ptr<Technique> t = tv.info->create(tv.params);
      t->prepare(s.frame.in);
      gl::throw_if_errors(tv.name + " prepare");
      return t;
    });
    for (int k = 1; k <= s.e.history_frames; ++k) {
      const std::string name = "measured sequence frame " + std::to_string(k);
      s.events.job_phase("render(), " + name);
      gl::PassTimer timer(s.timing_source);
      in_technique_phase(who, "render", [&] {
        render_frame(timer, *technique, name, gl::PassDetail::Coarse, s.frame, nullptr);
      });
    }
  }
  phases.frames = lap.seconds();

  s.events.job_phase("read-back");
  ImageF visibility = in_technique_phase(who, "read-back", [&] {
    ImageF v = s.frame.targets.read_visibility();
    gl::throw_if_errors(tv.name + " read-back");
    return v;
  });
  const VisibilityCheckRecord check = metrics::check_visibility(visibility);
  r.visibility_check = check;
  const bool invalid = check.nonfinite + check.below_0 + check.above_1 > 0;
  // The offending pixels of V as checked, before the attached-shadow mask
  // hides some: written even with --no-images, as the failure's evidence.
  if (invalid) r.images.add(write_invalid_visibility(s.o.run_dir, r.job_id, visibility));
  const MeasurementBasis& b = s.basis;
  s.events.job_phase("metrics");
  metrics::apply_attached_shadow(b.regions.attached, visibility);
  // Shaded from the same V as the metrics, as the reference is: untimed.
  const ImageF shaded = shade(s.frame, visibility);
  // The images that need no figure are written while the figures are
  // worked out: both run on the CPU with no frame running, and the images'
  // encoding fills the cores the metrics' serial steps leave idle.
  TaskAside images;
  record::ImagesRecord written;
  if (s.o.write_images)
    images.run([&] {
      written =
          write_job_images(s.o.run_dir, r.job_id, visibility, shaded, b.ref.visibility, b.regions);
    });
  ImageF flip_map;
  // Isolated: while it waits for its own parallel loops, this thread takes
  // none of the images' tasks, which would hold a loop's end back.
  tbb::this_task_arena::isolate(
      [&] { r.metrics = metrics::measure(visibility, shaded, *b.prepared, b.regions, &flip_map); });
  if (b.second)
    r.second_reference = SecondReferenceRecord{
        *b.second_record,
        metrics::measure_visibility(visibility, b.second->visibility, *b.second_flip, b.regions)};
  r.classes = ClassesRecord{metrics::confusion_matrix(visibility, b.ref.visibility,
                                                      b.regions.mask("geometry"), 1e-6f,
                                                      &b.regions.mask("penumbra"))};
  // Of a job that fails, no figure is compared: nor is its penumbra RMSE.
  if (!invalid)
    if (auto warning = metrics::noise_warning(*r.metrics, b.ref.penumbra_rms_std_error))
      r.warnings.push_back(*warning);
  phases.measure = lap.seconds();
  s.events.job_phase("images");
  if (s.o.write_images) {
    images.wait();
    r.images.add(written);
    r.images.add(write_flip_image(s.o.run_dir, r.job_id, flip_map));
  }
  phases.images = lap.seconds();
  // Metrics and images are kept for inspection (the executor moves the
  // figures into the record's "partial"), but the job fails.
  if (invalid)
    throw JobError("visibility outside [0,1]: " + std::to_string(check.nonfinite) + " NaN/Inf, " +
                   std::to_string(check.below_0) + " below 0, " + std::to_string(check.above_1) +
                   " above 1 (tolerance 1e-5)");
  // A broken job has no stability figures: it is broken.
  if (s.stability != nullptr) {
    s.events.job_phase("stability frames");
    r.stability = s.stability->measure(tv, *technique);
    gl::throw_if_errors(tv.name + " stability frames");
    phases.stability = lap.seconds();
  }
}

}  // namespace sb::run
