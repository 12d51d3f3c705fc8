#include "run/runner.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <map>
#include <thread>

#include "core/error.h"
#include "core/hash.h"
#include "gl/debug.h"
#include "gl/gpu_scene.h"
#include "metrics/image_io.h"
#include "metrics/light_horizon.h"
#include "metrics/metrics.h"
#include "plan/plan.h"
#include "record/job_record.h"
#include "reference/embree_isa.h"
#include "reference/reference.h"
#include "results/report.h"
#include "results/run_lock.h"
#include "results/store.h"
#include "run/gbuffer.h"
#include "run/progress.h"
#include "scenes/need_providers.h"
#include "scenes/receiver_inference.h"

namespace sb {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr int kSchemaVersion = 1;
constexpr float kHeatmapFullScale = 0.25f;

std::string now_iso8601() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// Non-finite components are written as strings, like every number of a record.
json vec_json(const glm::vec3& v) {
  return json::array({json_number(v.x), json_number(v.y), json_number(v.z)});
}

json stats_json(const metrics::ErrorStats& s) {
  return {{"pixel_count", s.pixel_count},
          {"rmse", json_number(s.rmse)},
          {"mae", json_number(s.mae)},
          {"max_error", json_number(s.max_error)},
          {"max_pixel", json::array({s.max_x, s.max_y})},
          {"psnr", json_number(s.psnr)},
          {"ssim", json_number(s.ssim)},
          {"frac_over_0.01", s.frac_over_001},
          {"frac_over_0.05", s.frac_over_005},
          {"frac_over_0.1", s.frac_over_01},
          {"nonfinite_count", s.nonfinite_count},
          {"mean_signed", json_number(s.mean_signed)}};
}

std::vector<uint8_t> mask_and(std::vector<uint8_t> a, const std::vector<uint8_t>& b) {
  for (size_t i = 0; i < a.size(); ++i) a[i] = a[i] && b[i] ? 1 : 0;
  return a;
}

// A technique's visibility must be finite and in [0,1]; float rounding of
// sums (accumulation, kernels) may overshoot by this much.
constexpr float kVisibilityTolerance = 1e-5f;  // the failure message says 1e-5

struct VisibilityCheck {
  size_t nonfinite = 0;
  size_t below_zero = 0;
  size_t above_one = 0;
};

VisibilityCheck check_visibility(const ImageF& v) {
  VisibilityCheck c;
  for (float x : v.data) {
    if (!std::isfinite(x))
      ++c.nonfinite;
    else if (x < -kVisibilityTolerance)
      ++c.below_zero;
    else if (x > 1.0f + kVisibilityTolerance)
      ++c.above_one;
  }
  return c;
}

// Pixels whose surface faces away from every point of the light are in
// attached shadow whatever any technique says: V = 0 there for every
// technique and the reference alike, so the error measures cast shadows only.
void apply_attached_shadow(const std::vector<uint8_t>& attached, ImageF& visibility) {
  for (size_t i = 0; i < attached.size(); ++i)
    if (attached[i]) visibility.data[i] = 0.0f;
}

// The unmeasured pixels (mask 0) take the reference's values: they show no
// error in the heat map and in SSIM's windows.
ImageF with_unmeasured_from(const ImageF& test, const ImageF& ref,
                            const std::vector<uint8_t>& measured) {
  ImageF out = test;
  for (size_t i = 0; i < measured.size(); ++i)
    if (!measured[i])
      for (int c = 0; c < out.channels; ++c)
        out.data[i * size_t(out.channels) + size_t(c)] =
            ref.data[i * size_t(ref.channels) + size_t(c)];
  return out;
}

// Three regions, each only over the measured pixels (all but those whose
// tangent plane cuts the light; see metrics/light_horizon.h): every pixel;
// the reference's penumbra; and the soft pixels of either the technique or
// the reference (`soft_union`), which also sees light bleeding into a true
// umbra and blur outside the true penumbra.
//
// SSIM's windows reach past the mask, so the unmeasured pixels take the
// reference's values first: they add no error to a neighbour either.
json compare_json(const ImageF& test, const ImageF& ref, const std::vector<uint8_t>& measured,
                  const std::vector<uint8_t>& penumbra, const std::vector<uint8_t>& soft_union) {
  const ImageF t = with_unmeasured_from(test, ref, measured);
  json j;
  j["all"] = stats_json(metrics::compare(t, ref, &measured));
  j["penumbra"] = stats_json(metrics::compare(t, ref, &penumbra));
  j["soft_union"] = stats_json(metrics::compare(t, ref, &soft_union));
  return j;
}

// Undo whatever state a technique left behind.
void reset_gl_state() { gl::reset_state(); }

// Pixel sets shared by every job of one (scene, resolution).
struct Regions {
  std::vector<uint8_t> measured;  // all but the pixels whose tangent plane cuts the light
  std::vector<uint8_t> penumbra;  // the reference's soft pixels, measured ones only
  std::vector<uint8_t> attached;  // the light wholly below the tangent plane: V = 0
};

// Per mesh: closed (depth passes may cull it; known when a technique in the
// plan asked for closedness) and, for receivers, whether nothing lies behind
// them from the light (filtered maps may draw them).
std::vector<MeshDrawFlags> draw_flags(const ScenePlan& st) {
  std::vector<MeshDrawFlags> flags(st.scene.meshes.size());
  const auto* topology = st.derived.find<CasterTopology>(need::kCasterClosedness);
  for (size_t i = 0; i < flags.size(); ++i) {
    const Mesh& m = st.scene.meshes[i];
    flags[i].closed = m.casts_shadow && topology != nullptr && (*topology)[i].closed();
    flags[i].nothing_behind = !m.casts_shadow && can_shadow_nothing(st.scene, i);
  }
  return flags;
}

class Runner {
 public:
  Runner(const Experiment& e, const RunOptions& o)
      : e_(e),
        o_(o),
        lock_(o.run_dir),
        store_(o.run_dir),
        progress_(stderr, !o.quiet && isatty(fileno(stderr)), 0) {}

  RunSummary run() {
    std::vector<std::string> order;
    for (const auto& s : e_.scenes)
      for (const auto& r : e_.resolutions)
        for (const auto& t : e_.techniques) order.push_back(job_id(s.name, r.label(), t.name));
    store_.set_order(order);
    total_ = order.size();
    progress_ = Progress(stderr, !o_.quiet && isatty(fileno(stderr)), total_);

    // The reference's ISA, once for the run: a CPU without it is the
    // environment's problem, found before any job runs.
    embree_config_ = !o_.embree_config.empty()             ? o_.embree_config
                     : !e_.reference.embree_config.empty() ? e_.reference.embree_config
                                                           : reference::default_embree_config();
    embree_isa_ = reference::resolve_isa(embree_config_);

    context_ = gl::create_context(o_.backend);
    timing_source_ =
        context_->is_software() ? gl::TimingSource::CpuFinish : gl::TimingSource::GpuQuery;
    log("backend " + context_->platform() + ", " + context_->renderer() + ", timing " +
        gl::to_string(timing_source_));

    for (const auto& sv : e_.scenes) run_scene(sv);
    progress_.clear();
    write_reports(store_.dir(), store_.records(), e_.name + " (" + o_.run_id + ")");
    return summary_;
  }

 private:
  void log(const std::string& line) const {
    if (o_.quiet) return;
    progress_.clear();
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
    progress_.draw();
  }

  json base_record(const SceneVariant& sv, const ScenePlan* st, const Resolution& res,
                   const TechniqueVariant& tv) const {
    json r;
    r["schema_version"] = kSchemaVersion;
    r["run_id"] = o_.run_id;
    r["config"] = e_.file;
    r["config_hash"] = e_.content_hash;
    r["experiment"] = e_.name;
    r["job_id"] = job_id(sv.name, res.label(), tv.name);
    r["spec_hash"] = spec_hash(sv, res, tv);
    r["scene_variant"] = sv.name;
    json scene = {{"type", sv.type}, {"variant", sv.name}, {"params", sv.params.json()}};
    if (st != nullptr) {
      scene["triangles"] = st->scene.triangle_count();
      scene["caster_triangles"] = st->scene.caster_triangle_count();
      const auto& l = st->scene.light;
      scene["light"] = {{"center", vec_json(l.center)},
                        {"target", vec_json(l.target)},
                        {"size", json::array({l.width(), l.height()})},
                        {"intensity", l.intensity}};
      const auto& c = st->scene.camera;
      scene["camera"] = {
          {"eye", vec_json(c.eye)}, {"target", vec_json(c.target)}, {"fov_y", c.fov_y_degrees}};
      scene["derived"] = {{"closedness_checked", st->derived.has(need::kCasterClosedness)},
                          {"adjacency_built", st->derived.has(need::kEdgeAdjacency)},
                          {"receiver_inference", sv.infer_receivers},
                          {"inferred_receivers", st->inferred_receivers}};
    }
    r["scene"] = scene;
    r["technique_variant"] = tv.name;
    r["technique"] = {{"name", tv.info->name},
                      {"family", tv.info->family},
                      {"variant", tv.name},
                      {"params", tv.params.json()}};
    r["resolution"] = res.label();
    r["width"] = res.width;
    r["height"] = res.height;
    r["backend"] = gl::to_string(o_.backend);
    r["gl_platform"] = context_->platform();
    r["gl_renderer"] = context_->renderer();
    r["gl_version"] = context_->version();
    r["timing_source"] = gl::to_string(timing_source_);
    r["host"] = {{"hardware_threads", std::thread::hardware_concurrency()}};
    // llvmpipe's rasteriser threads (read at context creation; default: cores).
    if (const char* lp = std::getenv("LP_NUM_THREADS")) r["host"]["lp_num_threads"] = lp;
    char host[256] = {};
    if (gethostname(host, sizeof host - 1) == 0) r["host"]["name"] = host;
    r["build"] = {{"version", SHADOWBENCH_VERSION}};
    return r;
  }

  // Everything in the config that decides a job's numbers. A rerun into the
  // same folder keeps a finished record only when its hash is the same.
  std::string spec_hash(const SceneVariant& sv, const Resolution& res,
                        const TechniqueVariant& tv) const {
    const json spec = {{"scene",
                        {{"type", sv.type},
                         {"params", sv.params.json()},
                         {"light", sv.light},
                         {"camera", sv.camera},
                         {"infer_receivers", sv.infer_receivers}}},
                       {"resolution", res.label()},
                       {"technique", {{"name", tv.info->name}, {"params", tv.params.json()}}},
                       {"frames", {e_.warmup_frames, e_.timed_frames}},
                       {"reference", {e_.reference.spp, e_.reference.seed, embree_isa_}},
                       {"backend", gl::to_string(o_.backend)}};
    Hasher h;
    h.add(json_text(spec));
    return h.hex();
  }

  bool resumable(const std::string& id, const std::string& hash) {
    const JobRecord* done = store_.finished(id);
    if (done == nullptr) return false;
    if (done->spec_hash == hash) return true;
    ++summary_.respecified;
    log("job " + id +
        ": its settings changed since the earlier run in this folder; running it again");
    return false;
  }

  void finish(json record) {
    record["finished_at"] = now_iso8601();
    const std::string status = record["status"];
    if (status == "ok") ++summary_.ok;
    if (status == "skipped") ++summary_.skipped;
    if (status == "failed") ++summary_.failed;
    store_.put(JobRecord::from_json(record));
    ++done_;
    // Jobs that rendered carry their duration; the rest took no time.
    if (record.contains("duration_s"))
      progress_.finish_job();
    else
      progress_.add_done_without_running(1);
    std::string line = "[" + std::to_string(done_) + "/" + std::to_string(total_) + "] " +
                       record["scene_variant"].get<std::string>() + " @ " +
                       record["resolution"].get<std::string>() + "  " +
                       record["technique_variant"].get<std::string>() + ": " + status;
    if (status == "ok") {
      char buf[128];
      std::snprintf(buf, sizeof buf, "  frame %.2f ms, technique %.2f ms, RMSE %.5f",
                    record["timing"]["frame"]["median_ms"].get<double>(),
                    record["timing"]["technique"]["median_ms"].get<double>(),
                    record["metrics"]["visibility"]["all"]["rmse"].is_number()
                        ? record["metrics"]["visibility"]["all"]["rmse"].get<double>()
                        : 0.0);
      line += buf;
    } else {
      line += " (" + record.value("reason", "") + ")";
    }
    log(line);
  }

  void run_scene(const SceneVariant& sv) {
    // Every decision is the plan's (plan/plan.h); the runner only executes.
    const ScenePlan st = plan_scene(e_, sv, Derive::All);
    const std::string& scene_error = st.error;
    for (const auto& l : st.log) log("scene " + sv.name + ": " + l);
    if (st.bad_input) {
      // A bad scene file: its jobs fail, the other scenes still run, and the
      // run's exit code says "bad input". Said even with --quiet.
      ++summary_.bad_input;
      progress_.clear();
      std::fprintf(stderr, "shadowbench: error: %s\n", st.input_error.c_str());
    }

    std::unique_ptr<GpuScene> gpu;
    DerivedData derived;  // the plan's, and the GPU stages' (freed before gpu)
    for (const auto& res : e_.resolutions) {
      // Pending jobs of this (scene, resolution); finished ones are kept.
      std::vector<size_t> pending;
      for (size_t i = 0; i < e_.techniques.size(); ++i) {
        const std::string id = job_id(sv.name, res.label(), e_.techniques[i].name);
        if (resumable(id, spec_hash(sv, res, e_.techniques[i]))) {
          ++summary_.resumed;
          ++done_;
          progress_.add_done_without_running(1);
          continue;
        }
        if (!scene_error.empty()) {
          json r = base_record(sv, nullptr, res, e_.techniques[i]);
          r["status"] = "failed";
          r["reason"] = scene_error;
          finish(r);
          continue;
        }
        if (!st.skip_reason[i].empty()) {
          json r = base_record(sv, &st, res, e_.techniques[i]);
          r["status"] = "skipped";
          r["reason"] = st.skip_reason[i];
          finish(r);
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
        // Shared work (G-buffer, reference) failed: every pending job fails.
        for (size_t i : pending) {
          const std::string id = job_id(sv.name, res.label(), e_.techniques[i].name);
          json r = base_record(sv, &st, res, e_.techniques[i]);
          r["status"] = "failed";
          r["reason"] = std::string("shared pass failed: ") + ex.what();
          finish(r);
        }
        gl::take_debug_errors();
        reset_gl_state();
      }
    }
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
    reference::Settings rs;
    rs.spp = e_.reference.spp;
    rs.seed = e_.reference.seed;
    rs.embree_config = embree_config_;
    const bool cache = e_.reference.cache && !o_.cache_dir.empty();
    progress_.start_job(sv.name, res.label(), "(reference)");
    reference::Result ref = cache ? reference::get(st.scene, positions, normals, rs, o_.cache_dir)
                                  : reference::compute(st.scene, positions, normals, rs);
    log("reference " + sv.name + " @ " + res.label() + ": " + std::to_string(ref.spp) + " spp, " +
        (ref.from_cache ? std::string("from cache") : std::to_string(ref.seconds) + " s") +
        ", mean std error " + std::to_string(ref.mean_std_error));
    const auto horizon = metrics::classify_light_horizon(positions, normals, st.scene.light);
    const std::vector<uint8_t> attached =
        metrics::horizon_mask(horizon, metrics::LightHorizon::Below);
    std::vector<uint8_t> measured = metrics::horizon_mask(horizon, metrics::LightHorizon::Cuts);
    for (auto& m : measured) m = m ? 0 : 1;
    apply_attached_shadow(attached, ref.visibility);
    const std::vector<uint8_t> penumbra =
        mask_and(metrics::penumbra_mask(ref.visibility), measured);

    targets.upload_visibility(ref.visibility);
    targets.render_shading(st.scene);
    const ImageF ref_shaded = targets.read_shaded();

    const std::string ref_rel = "reference/" + file_safe(sv.name) + "__" + res.label();
    json ref_images;
    if (o_.write_images) {
      fs::create_directories(fs::path(store_.dir()) / ref_rel);
      io::write_exr((fs::path(store_.dir()) / ref_rel / "visibility.exr").string(), ref.visibility);
      io::write_exr((fs::path(store_.dir()) / ref_rel / "std_error.exr").string(), ref.std_error);
      io::write_png((fs::path(store_.dir()) / ref_rel / "shaded.png").string(), ref_shaded);
      ref_images = {{"reference_visibility", ref_rel + "/visibility.exr"},
                    {"reference_std_error", ref_rel + "/std_error.exr"},
                    {"reference_shaded", ref_rel + "/shaded.png"}};
      if (o_.write_gbuffer) {
        io::write_exr((fs::path(store_.dir()) / ref_rel / "positions.exr").string(), positions);
        io::write_exr((fs::path(store_.dir()) / ref_rel / "normals.exr").string(), normals);
        ref_images["gbuffer_positions"] = ref_rel + "/positions.exr";
        ref_images["gbuffer_normals"] = ref_rel + "/normals.exr";
      }
    }
    json ref_json = {
        {"method", ref.method},
        {"spp", ref.spp},
        {"seed", ref.seed},
        {"embree_isa", ref.isa},
        {"embree_config", embree_config_},
        {"mean_std_error", ref.mean_std_error},
        {"penumbra_mean_std_error", ref.penumbra_mean_std_error},
        {"penumbra_rms_std_error", ref.penumbra_rms_std_error},
        {"penumbra_pixels", std::count(penumbra.begin(), penumbra.end(), uint8_t(1))},
        {"attached_shadow_pixels", std::count(attached.begin(), attached.end(), uint8_t(1))},
        {"horizon_cut_pixels", std::count(measured.begin(), measured.end(), uint8_t(0))},
        {"cache_key", ref.cache_key},
        {"from_cache", ref.from_cache},
        {"seconds", ref.seconds}};

    FrameInputs in = targets.inputs(st.scene, gpu, view, projection);
    in.derived = &derived;
    if (const auto* r = derived.find<PlanarReceiver>(need::kPlanarReceiver)) {
      in.has_receiver_plane = true;
      in.receiver_plane = r->plane;
    }
    for (size_t i : pending) {
      const TechniqueVariant& tv = e_.techniques[i];
      const std::string id = job_id(sv.name, res.label(), tv.name);
      progress_.start_job(sv.name, res.label(), tv.name);
      json r = base_record(sv, &st, res, tv);
      r["started_at"] = now_iso8601();
      r["reference"] = ref_json;
      const auto t0 = std::chrono::steady_clock::now();
      try {
        run_job(tv, targets, gpu, st.scene, view_projection, in, ref, ref_shaded,
                {measured, penumbra, attached}, id, r);
        for (const auto& [k, v] : ref_images.items()) r["images"][k] = v;
        r["status"] = "ok";
      } catch (const std::exception& ex) {
        r["status"] = "failed";
        r["reason"] = ex.what();
        gl::take_debug_errors();
      }
      r["duration_s"] =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      reset_gl_state();
      finish(r);
    }
  }

  void run_job(const TechniqueVariant& tv, FrameTargets& targets, const GpuScene& gpu,
               const Scene& scene, const glm::mat4& view_projection, const FrameInputs& in,
               const reference::Result& ref, const ImageF& ref_shaded, const Regions& regions,
               const std::string& id, json& r) {
    gl::take_debug_errors();
    std::unique_ptr<Technique> technique = tv.info->create(tv.params);
    technique->prepare(in);
    gl::throw_if_errors(tv.name + " prepare");

    gl::PassTimer timer(timing_source_);
    // One frame: the G-buffer, the technique and shading, each in one
    // harness bracket. In fine detail the technique's own passes are the
    // brackets instead, and the sum of their times is what it pays for them.
    const auto run_frame = [&](const std::string& frame_name, gl::PassDetail detail) {
      timer.set_detail(detail);
      reset_gl_state();
      timer.begin_frame();
      {
        auto p = timer.bracket("shared:gbuffer");
        targets.render_gbuffer(gpu, view_projection);
      }
      reset_gl_state();
      if (detail == gl::PassDetail::Coarse) {
        auto p = timer.bracket("technique");
        technique->render(in, timer);
      } else {
        technique->render(in, timer);
      }
      gl::throw_if_errors(tv.name + " " + frame_name);
      reset_gl_state();
      {
        auto p = timer.bracket("shared:shading");
        targets.render_shading(scene);
      }
      auto frame = timer.end_frame();
      gl::throw_if_errors(tv.name + " " + frame_name);
      return frame;
    };
    struct Samples {
      std::vector<double> frame, technique;
      std::map<std::string, std::vector<double>> passes, shared;
      std::vector<std::string> pass_order;
      void add(const gl::PassTimer::Frame& f) {
        frame.push_back(f.total_ms);
        double tech = 0.0;
        for (const auto& [name, ms] : f.passes) {
          if (name.rfind("shared:", 0) == 0) {
            shared[name.substr(7)].push_back(ms);
            continue;
          }
          if (name != "technique" && !passes.count(name)) pass_order.push_back(name);
          if (name != "technique") passes[name].push_back(ms);
          tech += ms;
        }
        technique.push_back(tech);
      }
    };
    Samples coarse, fine;
    const int frames = e_.warmup_frames + e_.timed_frames;
    // Frame -1 is never timed, whatever the warm-up count: shader compilation
    // and the driver's first-use work must not land in a timed frame (with
    // "warmup": 0 they would, and only for the techniques compiled last).
    for (int f = -1; f < frames; ++f) {
      const auto frame =
          run_frame(f < 0 ? "compile frame" : "frame " + std::to_string(f), gl::PassDetail::Coarse);
      if (f >= e_.warmup_frames) coarse.add(frame);
    }
    // Per-pass detail in frames of its own, so its syncs never reach the
    // technique's time above.
    if (o_.pass_detail == gl::PassDetail::Fine)
      for (int f = 0; f < e_.timed_frames; ++f)
        fine.add(run_frame("fine frame " + std::to_string(f), gl::PassDetail::Fine));

    json timing;
    timing["compile_frames"] = 1;
    timing["warmup_frames"] = e_.warmup_frames;
    timing["timed_frames"] = e_.timed_frames;
    timing["pass_timing"] = gl::to_string(o_.pass_detail);
    // Statistics plus the raw per-frame samples, in frame order: comparisons
    // between runs test the samples themselves (shadowbench compare).
    const auto with_samples = [](const std::vector<double>& v) {
      return TimingSeries::of(v).to_json();
    };
    timing["frame"] = with_samples(coarse.frame);
    timing["technique"] = with_samples(coarse.technique);
    for (const auto& [name, v] : coarse.shared) timing["shared"][name] = with_samples(v);
    if (o_.pass_detail == gl::PassDetail::Fine) {
      timing["passes"] = json::object();
      for (const auto& name : fine.pass_order)
        timing["passes"][name] = with_samples(fine.passes[name]);
      timing["pass_order"] = fine.pass_order;
      // The same frames' sums: what per-pass syncs cost, against "technique".
      timing["fine"] = {{"frames", e_.timed_frames},
                        {"technique", with_samples(fine.technique)},
                        {"frame", with_samples(fine.frame)}};
    }
    r["timing"] = timing;

    ImageF visibility = targets.read_visibility();
    const VisibilityCheck check = check_visibility(visibility);
    r["visibility_check"] = {{"nonfinite", check.nonfinite},
                             {"below_0", check.below_zero},
                             {"above_1", check.above_one},
                             {"tolerance", kVisibilityTolerance}};
    apply_attached_shadow(regions.attached, visibility);
    // Shaded from the same V as the metrics, as the reference is: untimed.
    targets.upload_visibility(visibility);
    targets.render_shading(scene);
    const ImageF shaded = targets.read_shaded();
    json m;
    const std::vector<uint8_t> soft_union =
        mask_and(metrics::soft_union_mask(visibility, ref.visibility), regions.measured);
    m["visibility"] =
        compare_json(visibility, ref.visibility, regions.measured, regions.penumbra, soft_union);
    m["shaded"] = compare_json(shaded, ref_shaded, regions.measured, regions.penumbra, soft_union);
    r["metrics"] = m;

    // A reference whose noise is comparable to the error cannot rank techniques.
    const double pen_rmse = m["visibility"]["penumbra"]["rmse"].is_number()
                                ? m["visibility"]["penumbra"]["rmse"].get<double>()
                                : 0.0;
    // RMS against RMS: the noise's sqrt(mean σ²), not its mean σ.
    if (ref.penumbra_rms_std_error > 0.0 && pen_rmse > 0.0 &&
        ref.penumbra_rms_std_error > 0.5 * pen_rmse)
      r["warnings"].push_back("reference noise (penumbra RMS std error " +
                              std::to_string(ref.penumbra_rms_std_error) +
                              ") is over half the penumbra RMSE; raise reference.spp");

    if (o_.write_images) {
      const std::string rel = "jobs/" + id;
      fs::create_directories(fs::path(store_.dir()) / rel);
      io::write_exr((fs::path(store_.dir()) / rel / "visibility.exr").string(), visibility);
      io::write_png((fs::path(store_.dir()) / rel / "shaded.png").string(), shaded);
      io::write_png(
          (fs::path(store_.dir()) / rel / "error.png").string(),
          metrics::error_heatmap(with_unmeasured_from(visibility, ref.visibility, regions.measured),
                                 ref.visibility, kHeatmapFullScale));
      r["images"] = {{"visibility", rel + "/visibility.exr"},
                     {"shaded", rel + "/shaded.png"},
                     {"error_heatmap", rel + "/error.png"},
                     {"error_heatmap_full_scale", kHeatmapFullScale}};
    }
    // Metrics and images are kept for inspection, but the job fails.
    if (check.nonfinite + check.below_zero + check.above_one > 0)
      throw JobError("visibility outside [0,1]: " + std::to_string(check.nonfinite) + " NaN/Inf, " +
                     std::to_string(check.below_zero) + " below 0, " +
                     std::to_string(check.above_one) + " above 1 (tolerance 1e-5)");
  }

  const Experiment& e_;
  const RunOptions& o_;
  RunFolderLock lock_;  // before store_: nothing is read until the folder is ours
  ResultsStore store_;
  std::unique_ptr<gl::Context> context_;
  gl::TimingSource timing_source_ = gl::TimingSource::CpuFinish;
  std::string embree_config_;  // as chosen: option, experiment, environment or ""
  std::string embree_isa_;     // what it resolves to on this CPU
  RunSummary summary_;
  size_t total_ = 0;
  size_t done_ = 0;
  mutable Progress progress_;  // drawn around log lines, which are const
};

}  // namespace

RunSummary run_experiment(const Experiment& experiment, const RunOptions& options) {
  return Runner(experiment, options).run();
}

}  // namespace sb
