#include "run/job_executor.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <set>
#include <utility>

#include "core/bounded_text.h"
#include "gl/debug.h"
#include "gl/objects.h"
#include "gl/shader_failures.h"
#include "metrics/regions.h"
#include "plan/plan.h"
#include "plugin/need_data.h"
#include "plugin/needs.h"
#include "record/job_record.h"
#include "run/failure_files.h"
#include "run/gbuffer.h"
#include "run/injected_delay.h"
#include "run/job_identity.h"
#include "run/job_run.h"
#include "run/measurement_basis.h"
#include "run/scene_upload.h"
#include "run/stability_probe.h"
#include "run/technique_frames.h"

namespace sb::run {

using config::Experiment;
using config::Resolution;
using config::SceneVariant;
using config::TechniqueVariant;
using core::ImageF;
using core::job_id;
using core::Scene;
using gl::GpuScene;
using plan::decide_job;
using plan::Derive;
using plan::derive_run_needs;
using plan::JobOutcome;
using plan::outcome_mismatch;
using plan::plan_scene;
using plan::PlannedJob;
using plan::ScenePlan;
using plugin::DerivedData;
using plugin::FrameInputs;
using plugin::PlanarReceiver;
using plugin::Technique;
using record::JobRecord;
using record::JobStatus;
using record::PhasesRecord;

namespace {

// Undo whatever state a technique left behind.
void reset_gl_state() { gl::reset_state(); }

// A job re-timed (run --retime) keeps what its kept record measured against
// the reference; its timing, host and session are this run's. A warning of
// an injected delay is the timing's, and is said again if it still applies.
void keep_measurements(const JobRecord& kept, JobRecord& r) {
  r.reference = kept.reference;
  r.visibility_check = kept.visibility_check;
  r.metrics = kept.metrics;
  r.second_reference = kept.second_reference;
  r.stability = kept.stability;
  r.classes = kept.classes;
  r.images = kept.images;
  for (const std::string& w : kept.warnings)
    if (w.find(kInjectDelayVariable) == std::string::npos) r.warnings.push_back(w);
  if (r.session)
    r.session->retimed_from =
        kept.session ? kept.session->id : std::string(record::kUnrecordedSession);
}

}  // namespace

class JobExecutor::Impl {
 public:
  Impl(const Experiment& e, const RunOptions& o, EmbreeChoice embree, RunEvents& events)
      : e_(e),
        o_(o),
        embree_(std::move(embree)),
        events_(events),
        injected_delay_(InjectedDelay::from_environment()) {
    context_ = gl::create_context(o_.backend);
    // Timestamps where the GL's clock can be trusted; CPU clocks otherwise.
    const bool timestamps = !context_->is_software() && gl::timestamp_queries_supported();
    timing_source_ = o_.timing_source.value_or(timestamps ? gl::TimingSource::GpuQuery
                                                          : gl::TimingSource::CpuFinish);
    events_.backend({context_->platform(), context_->renderer(), context_->version(),
                     gl::to_string(timing_source_)});
  }

  void run_scene(const SceneVariant& sv, const std::vector<ResolutionWork>& work,
                 ScenePlan* planned) {
    // The plan (made in the parent, before any GL context) decided every
    // job. Its build of the scene, when it kept one (a forked child's copy
    // of it), gets the Run needs' data; else the scene is built again, with
    // them, and must lead to the same decisions.
    std::optional<ScenePlan> rebuilt;
    if (planned != nullptr && planned->kept)
      derive_run_needs(e_, *planned);
    else
      rebuilt = plan_scene(e_, sv, Derive::All);
    const ScenePlan& st = rebuilt ? *rebuilt : *planned;
    events_.scene_planned(sv.name, st.log, st.bad_input ? st.input_error : std::string());

    UploadedScene uploaded;
    for (const ResolutionWork& w : work) {
      const Resolution& res = e_.resolutions[w.resolution];
      std::vector<size_t> pending;
      for (const PlannedJob* job : w.jobs) {
        const TechniqueVariant& tv = e_.techniques[job->technique];
        const ScenePlan* built = st.error.empty() ? &st : nullptr;
        const JobOutcome decided = decide_job(e_, st, job->technique);
        const std::string mismatch = outcome_mismatch(job->outcome, decided);
        if (!mismatch.empty())
          finish_unrun(sv, built, res, tv, JobStatus::Failed, mismatch);
        else if (decided.status == JobOutcome::Status::Fail)
          finish_unrun(sv, built, res, tv, JobStatus::Failed, decided.reason);
        else if (decided.status == JobOutcome::Status::Skip)
          finish_unrun(sv, built, res, tv, JobStatus::Skipped, decided.reason);
        else
          pending.push_back(job->technique);
      }
      if (pending.empty()) continue;
      try {
        // Both or neither: a failed GPU stage is tried again at the next
        // resolution, like a failed upload.
        if (!uploaded.gpu) uploaded = upload_scene(st);
        run_resolution(sv, st, uploaded, res, pending, w.retime);
      } catch (const std::exception& ex) {
        // Shared work (G-buffer, reference) failed: every job not yet
        // finished fails.
        for (size_t i : pending)
          if (!finished_.count(job_id(sv.name, res.label(), e_.techniques[i].name)))
            finish_unrun(sv, &st, res, e_.techniques[i], JobStatus::Failed,
                         std::string("shared pass failed: ") + ex.what());
        gl::take_debug_errors();
        reset_gl_state();
      }
    }
  }

  const Experiment& experiment() const { return e_; }

 private:
  // What identifies a job and where it ran; `st` is null for a scene that
  // did not build.
  JobRecord base_record(const SceneVariant& sv, const ScenePlan* st, const Resolution& res,
                        const TechniqueVariant& tv) const {
    // The files as this process's build of the scene read them; a scene
    // that did not build is identified by its files as they are now.
    JobRecord r = identity_record(e_, o_, embree_, sv,
                                  st != nullptr ? st->scene.inputs : std::vector<core::InputFile>{},
                                  res, tv, context_->renderer(), context_->version());
    if (st != nullptr) r.scene.built = built_scene(sv, *st);
    r.gl_platform = context_->platform();
    r.timing_source = gl::to_string(timing_source_);
    return r;
  }

  void finish(JobRecord record) {
    record.finished_at = now_iso8601();
    finished_.insert(record.job_id);
    events_.job_finished(std::move(record));
  }

  // A job that ends without rendering: skipped, or failed with the reason.
  void finish_unrun(const SceneVariant& sv, const ScenePlan* st, const Resolution& res,
                    const TechniqueVariant& tv, JobStatus status, const std::string& reason) {
    JobRecord r = base_record(sv, st, res, tv);
    r.status = status;
    r.reason = core::one_line_text(reason, core::kMessageChars);
    finish(std::move(r));
  }

  void run_resolution(const SceneVariant& sv, const ScenePlan& st, const UploadedScene& uploaded,
                      const Resolution& res, const std::vector<size_t>& pending,
                      const std::map<std::string, const JobRecord*>& retime) {
    const auto kept_record = [&](size_t i) -> const JobRecord* {
      const auto it = retime.find(job_id(sv.name, res.label(), e_.techniques[i].name));
      return it == retime.end() ? nullptr : it->second;
    };
    // Re-timed jobs measure nothing: without another job, no reference.
    const bool measures =
        std::any_of(pending.begin(), pending.end(), [&](size_t i) { return !kept_record(i); });
    const GpuScene& gpu = *uploaded.gpu;
    const DerivedData& derived = uploaded.derived;
    reset_gl_state();
    FrameTargets targets(res.width, res.height);
    const float aspect = float(res.width) / float(res.height);
    const glm::mat4 view = st.scene.camera.view();
    const glm::mat4 projection = st.scene.camera.projection(aspect);
    targets.render_gbuffer(gpu, projection * view);
    const MeasurementBasis basis =
        measures ? make_measurement_basis(e_, o_, embree_, events_, sv.name, st.scene, res, targets)
                 : MeasurementBasis{};

    FrameInputs in = targets.inputs(st.scene, gpu, view, projection);
    in.derived = &derived;
    if (const auto* r = derived.find<PlanarReceiver>(plugin::need::kPlanarReceiver)) {
      in.has_receiver_plane = true;
      in.receiver_plane = r->plane;
    }
    const FrameSetup frame{targets, st.scene, in};
    std::optional<StabilityProbe> stability;
    if (e_.stability && measures) {
      // Untimed frames under moved lights, measured against references of
      // the same lights at the same points.
      auto render = [&](Technique& t, const FrameInputs& moved) {
        const FrameSetup f{targets, *moved.scene, moved};
        gl::PassTimer timer(timing_source_);
        render_frame(timer, t, "stability frame", gl::PassDetail::Coarse, f, nullptr);
        ImageF v = targets.read_visibility();
        metrics::apply_attached_shadow(basis.regions.attached, v);
        reset_gl_state();
        return v;
      };
      auto reference = [&](const Scene& moved) {
        reference::Result out = basis.reference_of(moved);
        metrics::apply_attached_shadow(basis.regions.attached, out.visibility);
        return std::move(out.visibility);
      };
      stability.emplace(*e_.stability, sv.max_rmse.value_or(e_.stability->max_rmse), st.scene, in,
                        basis.regions.measured, render, reference, e_.history_frames);
    }
    std::optional<Control> control;
    if (e_.control) control = prepare_control(*e_.control, frame, timing_source_);
    const JobSetting setting{e_,
                             o_,
                             events_,
                             timing_source_,
                             injected_delay_ ? &*injected_delay_ : nullptr,
                             frame,
                             basis,
                             control ? &*control : nullptr,
                             stability ? &*stability : nullptr};
    for (size_t i : pending) {
      const TechniqueVariant& tv = e_.techniques[i];
      JobRecord r = base_record(sv, &st, res, tv);
      r.started_at = now_iso8601();
      const JobRecord* kept = kept_record(i);
      if (kept == nullptr) r.reference = basis.ref_record;
      events_.job_started(r);
      const auto t0 = std::chrono::steady_clock::now();
      PhasesRecord phases;
      (void)gl::take_failed_shaders();  // another job's, or the shared passes'
      try {
        run_job(setting, tv, uploaded.gpu_bytes_held_for(st.needs.at(i)), r, phases,
                kept != nullptr);
        if (kept != nullptr)
          keep_measurements(*kept, r);  // once timed: a failed re-timing has none
        else
          r.images.add(basis.ref_images);
        r.status = JobStatus::Ok;
      } catch (const std::exception& ex) {
        r.status = JobStatus::Failed;
        // One table row; a compiler's log and the shaders it counts lines
        // of go to files beside the job's images.
        r.reason = failure_reason(o_.run_dir, r.job_id, ex.what(), gl::take_failed_shaders());
        r.set_aside_failed_measurements();  // a failed job carries no figures
        gl::take_debug_errors();
      }
      reset_gl_state();
      r.duration_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      r.overhead_s = phases.overhead(*r.duration_s);
      r.phases_s = phases;
      finish(std::move(r));
    }
  }

  const Experiment& e_;
  const RunOptions& o_;
  EmbreeChoice embree_;
  RunEvents& events_;
  std::unique_ptr<gl::Context> context_;
  gl::TimingSource timing_source_ = gl::TimingSource::CpuFinish;
  std::set<std::string> finished_;  // job ids with a record from this process
  // SHADOWBENCH_INJECT_DELAY: a known slowdown, to measure the CI gate.
  std::optional<InjectedDelay> injected_delay_;
};

JobExecutor::JobExecutor(const Experiment& e, const RunOptions& o, EmbreeChoice embree,
                         RunEvents& events)
    : impl_(std::make_unique<Impl>(e, o, std::move(embree), events)) {}

JobExecutor::~JobExecutor() = default;

void JobExecutor::run_scene(size_t scene, const std::vector<ResolutionWork>& work,
                            plan::ScenePlan* planned) {
  impl_->run_scene(impl_->experiment().scenes.at(scene), work, planned);
}

}  // namespace sb::run
