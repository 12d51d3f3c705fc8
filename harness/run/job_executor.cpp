#include "run/job_executor.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <optional>
#include <set>
#include <utility>

#include "core/error.h"
#include "gl/debug.h"
#include "gl/gl.h"
#include "gl/gpu_scene.h"
#include "metrics/distance_thirds.h"
#include "metrics/geometry_region.h"
#include "metrics/image_io.h"
#include "metrics/job_metrics.h"
#include "metrics/light_horizon.h"
#include "metrics/metrics.h"
#include "metrics/regions.h"
#include "metrics/shadow_classes.h"
#include "plan/plan.h"
#include "record/job_record.h"
#include "reference/reference.h"
#include "results/store.h"
#include "run/frame_schedule.h"
#include "run/gbuffer.h"
#include "run/injected_delay.h"
#include "run/job_identity.h"
#include "run/stability_probe.h"
#include "run/technique_frames.h"
#include "run/technique_phase.h"
#include "scenes/need_providers.h"
#include "scenes/receiver_inference.h"

namespace sb {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr float kHeatmapFullScale = 0.25f;

std::array<double, 3> vec3(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// Undo whatever state a technique left behind.
void reset_gl_state() { gl::reset_state(); }

// What every job of one (scene, resolution) is measured against.
struct Baseline {
  const reference::Result& ref;
  const ImageF& shaded;  // the reference's V, shaded
  const metrics::Regions& regions;
  // reference.second_method's reference, and its record part.
  const reference::Result* second = nullptr;
  const ReferenceRecord* second_record = nullptr;
  StabilityProbe* stability = nullptr;  // the "stability" block
};

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

// Per mesh: closed (depth passes may cull it; known when a technique in the
// plan asked for closedness) and, for receivers, whether nothing lies behind
// them from the light (filtered maps may draw them).
std::vector<MeshDrawFlags> draw_flags(const ScenePlan& st) {
  std::vector<MeshDrawFlags> flags(st.scene.meshes.size());
  const auto* topology = st.derived.find<CasterTopology>(need::kCasterClosedness);
  const ShadowNothingTest shadows_nothing(st.scene);
  for (size_t i = 0; i < flags.size(); ++i) {
    const Mesh& m = st.scene.meshes[i];
    flags[i].closed = m.casts_shadow && topology != nullptr && (*topology)[i].closed();
    flags[i].nothing_behind = !m.casts_shadow && shadows_nothing(i);
  }
  return flags;
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

  void run_scene(const SceneVariant& sv, const std::vector<ResolutionWork>& work) {
    // Every decision is the plan's (plan/plan.h); the executor only executes.
    const ScenePlan st = plan_scene(e_, sv, Derive::All);
    events_.scene_planned(sv.name, st.log, st.bad_input ? st.input_error : std::string());

    std::unique_ptr<GpuScene> gpu;
    DerivedData derived;  // the plan's, and the GPU stages' (freed before gpu)
    for (const ResolutionWork& w : work) {
      const Resolution& res = e_.resolutions[w.resolution];
      std::vector<size_t> pending;
      for (size_t i : w.techniques) {
        if (!e_.techniques[i].unavailable.empty()) {  // its plugin failed to load
          finish_unrun(sv, st.error.empty() ? &st : nullptr, res, e_.techniques[i],
                       JobStatus::Failed, e_.techniques[i].unavailable);
          continue;
        }
        if (!st.error.empty()) {
          finish_unrun(sv, nullptr, res, e_.techniques[i], JobStatus::Failed, st.error);
          continue;
        }
        if (!st.skip_reason[i].empty()) {
          finish_unrun(sv, &st, res, e_.techniques[i], JobStatus::Skipped, st.skip_reason[i]);
          continue;
        }
        pending.push_back(i);
      }
      if (pending.empty()) continue;
      try {
        if (!gpu) {
          // Both or neither: a failed GPU stage is tried again at the next
          // resolution, like a failed upload.
          const auto* adjacency = st.derived.find<CasterAdjacency>(need::kEdgeAdjacency);
          auto uploaded = std::make_unique<GpuScene>(
              st.scene, adjacency ? *adjacency : CasterAdjacency{}, draw_flags(st));
          DerivedData with_gpu = st.derived;
          for (const NeedProvider* p : st.uploads) p->upload(st.scene, *uploaded, with_gpu);
          gpu = std::move(uploaded);
          derived = std::move(with_gpu);
        }
        run_resolution(sv, st, *gpu, derived, res, pending);
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
  void log(const std::string& line) const { events_.log(line); }

  // What identifies a job and where it ran; `st` is null for a scene that
  // did not build.
  JobRecord base_record(const SceneVariant& sv, const ScenePlan* st, const Resolution& res,
                        const TechniqueVariant& tv) const {
    JobRecord r =
        identity_record(e_, o_, embree_, sv, res, tv, context_->renderer(), context_->version());
    if (st != nullptr) {
      BuiltScene b;
      b.triangles = static_cast<std::int64_t>(st->scene.triangle_count());
      b.caster_triangles = static_cast<std::int64_t>(st->scene.caster_triangle_count());
      b.analytic_casters = static_cast<std::int64_t>(st->scene.analytic_caster_count());
      const auto& l = st->scene.light;
      b.light = {vec3(l.center), vec3(l.target), {l.width(), l.height()}, l.intensity};
      const auto& c = st->scene.camera;
      b.camera = {vec3(c.eye), vec3(c.target), c.fov_y_degrees};
      b.derived = {st->derived.has(need::kCasterClosedness), st->derived.has(need::kEdgeAdjacency),
                   sv.infer_receivers, st->inferred_receivers};
      r.scene.built = std::move(b);
    }
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
    r.reason = reason;
    finish(std::move(r));
  }

  // The reference's part of every record of one (scene, resolution).
  // `penumbra`: the reference's own soft pixels.
  ReferenceRecord reference_record(const reference::Result& ref, const metrics::Regions& regions,
                                   const std::vector<uint8_t>& penumbra) const {
    ReferenceRecord r;
    r.method = ref.method;
    r.exact_fallback = ref.exact_fallback;
    r.spp = ref.spp;
    r.seed = ref.seed;
    r.embree_isa = ref.isa;
    r.embree_config = embree_.config;
    r.mean_std_error = ref.mean_std_error;
    r.penumbra_mean_std_error = ref.penumbra_mean_std_error;
    r.penumbra_rms_std_error = ref.penumbra_rms_std_error;
    r.penumbra_pixels = metrics::count_ones(penumbra);
    r.attached_shadow_pixels = metrics::count_ones(regions.attached);
    r.horizon_cut_pixels =
        static_cast<std::int64_t>(regions.measured.size()) - metrics::count_ones(regions.measured);
    r.cache_key = ref.cache_key;
    r.from_cache = ref.from_cache;
    r.seconds = ref.seconds;
    if (ref.method == reference::kAdaptiveMethod)
      r.adaptive = AdaptiveReferenceRecord{e_.reference.settings.pilot_spp,
                                           e_.reference.settings.target_std_error,
                                           ref.mean_spp,
                                           ref.max_spp,
                                           ref.unproven_stops,
                                           ref.stop_bias_bound};
    return r;
  }

  // The reference's images, the masks of the regions every job shares (and
  // with --gbuffer the G-buffer's), once per (scene, resolution); every
  // job's record names them.
  ImagesRecord write_reference_images(const std::string& rel, const reference::Result& ref,
                                      const ImageF& ref_shaded, const metrics::Regions& regions,
                                      const ImageF& positions, const ImageF& normals) const {
    ImagesRecord images;
    if (!o_.write_images) return images;
    const fs::path dir = fs::path(o_.run_dir) / rel;
    fs::create_directories(dir);
    io::write_exr((dir / "visibility.exr").string(), ref.visibility);
    io::write_exr((dir / "std_error.exr").string(), ref.std_error);
    io::write_png((dir / "shaded.png").string(), ref_shaded);
    images.reference_visibility = rel + "/visibility.exr";
    images.reference_std_error = rel + "/std_error.exr";
    images.reference_shaded = rel + "/shaded.png";
    // Named as the record's metrics.visibility regions; soft_union is each job's own.
    std::vector<std::pair<std::string, const std::vector<uint8_t>*>> masks = {
        {"all", &regions.measured},
        {"geometry", &regions.geometry},
        {"penumbra", &regions.penumbra}};
    if (regions.any_receiver) masks.emplace_back("receivers", &regions.receivers);
    if (regions.distance_thirds) {
      const char* names[3] = {"near_third", "middle_third", "far_third"};
      for (size_t i = 0; i < 3; ++i) masks.emplace_back(names[i], &(*regions.distance_thirds)[i]);
    }
    for (const auto& [region, mask] : masks) {
      const std::string file = "mask_" + region + ".png";
      io::write_mask_png((dir / file).string(), *mask, ref.visibility.width, ref.visibility.height);
      images.masks[region] = (fs::path(rel) / file).generic_string();
    }
    if (o_.write_gbuffer) {
      io::write_exr((dir / "positions.exr").string(), positions);
      io::write_exr((dir / "normals.exr").string(), normals);
      images.gbuffer_positions = rel + "/positions.exr";
      images.gbuffer_normals = rel + "/normals.exr";
    }
    return images;
  }

  void run_resolution(const SceneVariant& sv, const ScenePlan& st, const GpuScene& gpu,
                      const DerivedData& derived, const Resolution& res,
                      const std::vector<size_t>& pending) {
    reset_gl_state();
    FrameTargets targets(res.width, res.height);
    const float aspect = float(res.width) / float(res.height);
    const glm::mat4 view = st.scene.camera.view();
    const glm::mat4 projection = st.scene.camera.projection(aspect);
    const glm::mat4 view_projection = projection * view;
    targets.render_gbuffer(gpu, view_projection);
    const ImageF positions = targets.read_positions();
    const ImageF normals = targets.read_geometric_normals();

    // Reference at the G-buffer's very points.
    const reference::Settings rs =
        reference_settings(e_.reference, embree_, e_.reference.settings.exact);
    const bool cache = e_.reference.cache && !o_.cache_dir.empty();
    events_.phase(sv.name, res.label(), "(reference)");
    const auto make_reference = [&](const reference::Settings& settings, const char* which) {
      reference::Result out =
          cache ? reference::get(st.scene, positions, normals, settings, o_.cache_dir)
                : reference::compute(st.scene, positions, normals, settings);
      // The key names the reference in the record even when nothing is
      // cached, so that `compare` can tell two references apart.
      if (out.cache_key.empty()) {
        reference::Settings keyed = settings;
        if (!out.exact_fallback.empty()) keyed.exact = false;  // as reference::get keys it
        out.cache_key = reference::cache_key(st.scene, positions, normals, keyed);
      }
      const std::string samples = out.method == reference::kExactMethod ? std::string("exact")
                                  : out.method == reference::kAdaptiveMethod
                                      ? "adaptive, mean " + std::to_string(out.mean_spp) + " of " +
                                            std::to_string(out.spp) + " spp"
                                      : std::to_string(out.spp) + " spp";
      log(std::string(which) + " " + sv.name + " @ " + res.label() + ": " + samples + ", " +
          (out.from_cache ? std::string("from cache") : std::to_string(out.seconds) + " s") +
          ", mean std error " + std::to_string(out.mean_std_error));
      if (!out.exact_fallback.empty())
        log(std::string(which) + " " + sv.name + ": Monte Carlo, not exact: " + out.exact_fallback);
      return out;
    };
    reference::Result ref = make_reference(rs, "reference");
    std::optional<reference::Result> second;
    if (e_.reference.second_exact) {
      events_.phase(sv.name, res.label(), "(second reference)");
      second = make_reference(reference_settings(e_.reference, embree_, *e_.reference.second_exact),
                              "second reference");
    }
    const auto horizon = metrics::classify_light_horizon(positions, normals, st.scene.light);
    metrics::Regions regions;
    regions.attached = metrics::horizon_mask(horizon, metrics::LightHorizon::Below);
    regions.measured = metrics::horizon_mask(horizon, metrics::LightHorizon::Cuts);
    for (auto& m : regions.measured) m = m ? 0 : 1;
    metrics::apply_attached_shadow(regions.attached, ref.visibility);
    regions.penumbra = metrics::mask_and(metrics::penumbra_mask(ref.visibility), regions.measured);
    regions.geometry = metrics::geometry_mask(horizon);
    if (e_.distance_thirds)
      regions.distance_thirds =
          metrics::distance_thirds(positions, st.scene.camera.eye, regions.measured);
    std::optional<ReferenceRecord> second_record;
    if (second) {
      metrics::apply_attached_shadow(regions.attached, second->visibility);
      second_record = reference_record(
          *second, regions,
          metrics::mask_and(metrics::penumbra_mask(second->visibility), regions.measured));
    }
    {
      const ImageF receiver = targets.read_receiver_mask();
      regions.receivers.resize(receiver.data.size());
      for (size_t i = 0; i < receiver.data.size(); ++i)
        regions.receivers[i] = receiver.data[i] != 0.0f && regions.measured[i] ? 1 : 0;
      regions.any_receiver = std::find(regions.receivers.begin(), regions.receivers.end(), 1) !=
                             regions.receivers.end();
    }

    targets.upload_visibility(ref.visibility);
    targets.render_shading(st.scene);
    const ImageF ref_shaded = targets.read_shaded();

    const ImagesRecord ref_images =
        write_reference_images("reference/" + file_safe(sv.name) + "__" + res.label(), ref,
                               ref_shaded, regions, positions, normals);
    const ReferenceRecord ref_record = reference_record(ref, regions, regions.penumbra);

    FrameInputs in = targets.inputs(st.scene, gpu, view, projection);
    in.derived = &derived;
    if (const auto* r = derived.find<PlanarReceiver>(need::kPlanarReceiver)) {
      in.has_receiver_plane = true;
      in.receiver_plane = r->plane;
    }
    const FrameSetup frame{targets, st.scene, in};
    std::optional<StabilityProbe> stability;
    if (e_.stability) {
      // Untimed frames under moved lights, measured against references of
      // the same lights at the same points.
      auto render = [&](Technique& t, const FrameInputs& moved) {
        const FrameSetup f{targets, *moved.scene, moved};
        gl::PassTimer timer(timing_source_);
        render_frame(timer, t, "stability frame", gl::PassDetail::Coarse, f, nullptr);
        ImageF v = targets.read_visibility();
        metrics::apply_attached_shadow(regions.attached, v);
        reset_gl_state();
        return v;
      };
      auto reference = [&, settings = rs](const Scene& moved) {
        reference::Result out =
            cache ? reference::get(moved, positions, normals, settings, o_.cache_dir)
                  : reference::compute(moved, positions, normals, settings);
        metrics::apply_attached_shadow(regions.attached, out.visibility);
        return std::move(out.visibility);
      };
      stability.emplace(*e_.stability, sv.max_rmse.value_or(e_.stability->max_rmse), st.scene, in,
                        regions.measured, render, reference);
    }
    const Baseline baseline{ref,
                            ref_shaded,
                            regions,
                            second ? &*second : nullptr,
                            second_record ? &*second_record : nullptr,
                            stability ? &*stability : nullptr};
    std::optional<Control> control;
    if (e_.control) control = prepare_control(*e_.control, frame, timing_source_);
    for (size_t i : pending) {
      const TechniqueVariant& tv = e_.techniques[i];
      JobRecord r = base_record(sv, &st, res, tv);
      r.started_at = now_iso8601();
      r.reference = ref_record;
      events_.job_started(r);
      const auto t0 = std::chrono::steady_clock::now();
      PhasesRecord phases;
      try {
        run_job(tv, frame, baseline, control ? &*control : nullptr, r, phases);
        r.images.add(ref_images);
        r.status = JobStatus::Ok;
      } catch (const std::exception& ex) {
        r.status = JobStatus::Failed;
        r.reason = ex.what();
        gl::take_debug_errors();
      }
      reset_gl_state();
      r.duration_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      r.overhead_s = phases.overhead(*r.duration_s);
      r.phases_s = phases;
      finish(std::move(r));
    }
  }

  // One job: prepare the technique, time it, check and measure its V, write
  // its images. Whatever it got to stays in `r` when it throws.
  void run_job(const TechniqueVariant& tv, const FrameSetup& frame, const Baseline& baseline,
               Control* control, JobRecord& r, PhasesRecord& phases) {
    Lap lap;
    gl::take_debug_errors();
    const std::string& who = tv.info->name;
    std::unique_ptr<Technique> technique = in_technique_phase(who, "prepare", [&] {
      std::unique_ptr<Technique> t = tv.info->create(tv.params);
      t->prepare(frame.in);
      gl::throw_if_errors(tv.name + " prepare");
      glFinish();  // prepare's GL work in prepare's time, not the first frame's
      return t;
    });
    phases.prepare = lap.seconds();
    // The parent stores the record before this one while prepare runs; no
    // write of its overlaps a frame (docs/robustness.md). Its wait is
    // overhead, in no phase.
    events_.await_listener();
    lap.seconds();

    const InjectedDelay* delay =
        injected_delay_ && injected_delay_->applies_to(tv.name) ? &*injected_delay_ : nullptr;
    TechniqueFrames frames(frame, *technique, who, control, delay, timing_source_,
                           [&] { o_.take_turn(tv.name); });
    FrameSchedule schedule;
    schedule.job = tv.name;
    schedule.warmup_frames = e_.warmup_frames;
    schedule.timed_frames = e_.timed_frames;
    if (control != nullptr) schedule.control = control->name;
    schedule.pass_detail = o_.pass_detail;
    schedule.turn_block_frames = o_.take_turn ? o_.turn_block_frames : 0;
    r.timing = time_frames(frames, schedule);
    phases.frames = lap.seconds();
    if (delay != nullptr) r.warnings.push_back(delay->describe());

    ImageF visibility = in_technique_phase(who, "read-back", [&] {
      ImageF v = frame.targets.read_visibility();
      gl::throw_if_errors(tv.name + " read-back");
      return v;
    });
    const VisibilityCheckRecord check = metrics::check_visibility(visibility);
    r.visibility_check = check;
    metrics::apply_attached_shadow(baseline.regions.attached, visibility);
    // Shaded from the same V as the metrics, as the reference is: untimed.
    const ImageF shaded = shade(frame, visibility);
    r.metrics = metrics::measure(visibility, shaded, baseline.ref.visibility, baseline.shaded,
                                 baseline.regions);
    if (baseline.second)
      r.second_reference = SecondReferenceRecord{
          *baseline.second_record,
          metrics::measure_visibility(visibility, baseline.second->visibility, baseline.regions)};
    r.classes = ClassesRecord{
        metrics::confusion_matrix(visibility, baseline.ref.visibility, baseline.regions.geometry)};
    if (auto warning = metrics::noise_warning(*r.metrics, baseline.ref.penumbra_rms_std_error))
      r.warnings.push_back(*warning);
    phases.measure = lap.seconds();
    if (o_.write_images) r.images = write_job_images(r.job_id, visibility, shaded, baseline);
    phases.images = lap.seconds();
    // Metrics and images are kept for inspection, but the job fails.
    if (check.nonfinite + check.below_0 + check.above_1 > 0)
      throw JobError("visibility outside [0,1]: " + std::to_string(check.nonfinite) + " NaN/Inf, " +
                     std::to_string(check.below_0) + " below 0, " + std::to_string(check.above_1) +
                     " above 1 (tolerance 1e-5)");
    // A broken job has no stability figures: it is broken.
    if (baseline.stability) {
      r.stability = baseline.stability->measure(tv, *technique);
      gl::throw_if_errors(tv.name + " stability frames");
      phases.stability = lap.seconds();
    }
  }

  // The technique's V, its shaded image and its error heat map.
  ImagesRecord write_job_images(const std::string& id, const ImageF& visibility,
                                const ImageF& shaded, const Baseline& b) const {
    const std::string rel = "jobs/" + id;
    const fs::path dir = fs::path(o_.run_dir) / rel;
    fs::create_directories(dir);
    // Four files at once: no frame runs now, and one file's encoding keeps
    // one core busy (zlib), so the job's images take about half the time.
    tbb::parallel_invoke(
        [&] {
          io::write_mask_png(
              (dir / "mask_soft_union.png").string(),
              metrics::soft_union_of(visibility, b.ref.visibility, b.regions.measured),
              visibility.width, visibility.height);
        },
        [&] { io::write_exr((dir / "visibility.exr").string(), visibility); },
        [&] { io::write_png((dir / "shaded.png").string(), shaded); },
        [&] {
          io::write_png(
              (dir / "error.png").string(),
              metrics::error_heatmap(
                  metrics::with_unmeasured_from(visibility, b.ref.visibility, b.regions.measured),
                  b.ref.visibility, kHeatmapFullScale));
        });
    ImagesRecord images;
    images.visibility = rel + "/visibility.exr";
    images.shaded = rel + "/shaded.png";
    images.error_heatmap = rel + "/error.png";
    images.error_heatmap_full_scale = kHeatmapFullScale;
    images.masks["soft_union"] = rel + "/mask_soft_union.png";
    return images;
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

void JobExecutor::run_scene(size_t scene, const std::vector<ResolutionWork>& work) {
  impl_->run_scene(impl_->experiment().scenes.at(scene), work);
}

}  // namespace sb
