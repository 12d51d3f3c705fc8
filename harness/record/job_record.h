#pragma once
// One job's record, as `run` writes it (records/<job_id>.json, one line of
// results.jsonl) and every reader reads it: docs/results.md, "Record schema".
//
// to_json() writes schema_version 1 exactly as documented: members that a job
// did not reach (a skipped job's timing, a failed scene's light) are absent,
// not null. from_json() reads it back or throws RecordError naming the JSON
// pointer of what is wrong; a record of another schema_version is refused.
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "record/classes_record.h"
#include "record/describe.h"
#include "record/fields.h"
#include "record/host_record.h"
#include "record/metrics_record.h"
#include "record/phases_record.h"
#include "record/reference_record.h"
#include "record/scene_record.h"
#include "record/second_reference_record.h"
#include "record/session_record.h"
#include "record/stability_record.h"
#include "record/timing_record.h"

namespace sb::record {

// The schema_version this build writes and reads.
inline constexpr int kRecordSchemaVersion = 1;

enum class JobStatus { Ok, Skipped, Failed };
const char* to_string(JobStatus s);  // "ok", "skipped", "failed"
// The record's "status": throws RecordError for any other string.
JobStatus status_from(const Fields& f);

// Pixels of the technique's visibility (before the attached-shadow mask)
// that are not finite or outside [0, 1] by more than the tolerance.
struct VisibilityCheckRecord {
  static constexpr RecordDoc kSchema{
      "VisibilityCheckRecord",
      "pixels of the technique's visibility (before the attached-shadow mask) that are NaN/Inf "
      "or outside [0, 1] by more than `tolerance`: any of them fails the job, whose timing "
      "and metrics are still recorded for inspection under `partial`, and its images "
      "with `images.invalid`, the offending pixels"};

  std::int64_t nonfinite = 0;
  std::int64_t below_0 = 0;
  std::int64_t above_1 = 0;
  double tolerance = 0;

  template <class V>
  static void describe(V& v) {
    using C = VisibilityCheckRecord;
    v.field("nonfinite", &C::nonfinite, {"px", "NaN or infinite"});
    v.field("below_0", &C::below_0, {"px", "below 0 by more than the tolerance"});
    v.field("above_1", &C::above_1, {"px", "above 1 by more than the tolerance"});
    v.field("tolerance", &C::tolerance, {"", "1e-5"});
  }
};

// What a failed job measured before it failed (record["partial"]): kept for
// inspection under a name that says so, and read by no table, chart,
// comparison or history series (docs/results.md, "Failed jobs").
struct PartialRecord {
  static constexpr RecordDoc kSchema{
      "PartialRecord",
      "what a failed job had measured when it failed, kept for inspection and shown by no "
      "table, chart, comparison or history series: the figures an `ok` record has in `timing`, "
      "`technique.gpu_bytes` with its parts, `metrics`, `second_reference` and `classes`. A failed "
      "record "
      "written before `partial` existed has them there; reading it moves them here"};

  std::optional<TimingRecord> timing;
  std::optional<std::int64_t> gpu_bytes, gpu_own_bytes;
  std::optional<std::map<std::string, std::int64_t>> gpu_need_bytes;
  std::optional<MetricsRecord> metrics;
  std::optional<SecondReferenceRecord> second_reference;
  std::optional<ClassesRecord> classes;

  template <class V>
  static void describe(V& v) {
    using P = PartialRecord;
    v.field("timing", &P::timing, {"", "the frames' times, as `timing`"});
    v.field("gpu_bytes", &P::gpu_bytes,
            {"bytes", "the technique's GPU memory, as `technique.gpu_bytes`"});
    v.field("gpu_own_bytes", &P::gpu_own_bytes, {"bytes", "as `technique.gpu_own_bytes`"});
    v.field("gpu_need_bytes", &P::gpu_need_bytes, {"bytes", "as `technique.gpu_need_bytes`"});
    v.field("metrics", &P::metrics, {"", "the errors, as `metrics`"});
    v.field("second_reference", &P::second_reference, {"", "as `second_reference`"});
    v.field("classes", &P::classes, {"", "as `classes`"});
  }

  bool empty() const {
    return !timing && !gpu_bytes && !gpu_own_bytes && !gpu_need_bytes && !metrics &&
           !second_reference && !classes;
  }
};

// Paths relative to the run directory; each present only when written.
struct ImagesRecord {
  static constexpr RecordDoc kSchema{
      "ImagesRecord",
      "the images written (not with `--no-images`): paths relative to the run directory"};

  std::optional<std::string> visibility, shaded, error_heatmap, flip_shaded;
  std::optional<double> error_heatmap_full_scale;
  std::optional<std::string> reference_visibility, reference_std_error, reference_shaded;
  std::optional<std::string> reference_stop_bound;
  std::optional<std::string> gbuffer_positions, gbuffer_normals;  // run --gbuffer
  // A failed visibility check's pixels, by kind (run/run_images.h).
  std::optional<std::string> invalid;
  // The pixels each metrics.visibility region measured, by region name (an
  // 8-bit PNG, 255 = measured): what recomputes the record's errors from
  // the files (docs/results.md "Recomputing the errors").
  std::map<std::string, std::string> masks;

  template <class V>
  static void describe(V& v) {
    using I = ImagesRecord;
    v.field("visibility", &I::visibility, {"", "the technique's V (EXR)"});
    v.field("shaded", &I::shaded, {"", "the shaded image (PNG)"});
    v.field("error_heatmap", &I::error_heatmap, {"", "|V − reference| as colours (PNG)"});
    v.field("error_heatmap_full_scale", &I::error_heatmap_full_scale,
            {"", "the error shown as the brightest colour"});
    v.field("flip_shaded", &I::flip_shaded,
            {"",
             "the shaded image's FLIP map over every pixel (`metrics.flip_shaded`; "
             "records written before it hold the map of `metrics.shaded.all.flip_mean`) in the "
             "heat-map colours, 0 to 1 (PNG); absent from older records"});
    v.field("reference_visibility", &I::reference_visibility, {"", "the reference's V"});
    v.field("reference_std_error", &I::reference_std_error,
            {"", "its standard error σ, 0 where the samples all agreed"});
    v.field("reference_stop_bound", &I::reference_stop_bound,
            {"",
             "its stop bound where the samples all agreed with no proof (`reference."
             "stopped_pixels`), 0 elsewhere (EXR); absent from older records"});
    v.field("reference_shaded", &I::reference_shaded, {"", "shaded from it"});
    v.field("gbuffer_positions", &I::gbuffer_positions, {"", "with `run --gbuffer`"});
    v.field("gbuffer_normals", &I::gbuffer_normals, {"", "with `run --gbuffer`"});
    v.field("invalid", &I::invalid,
            {"",
             "when `visibility_check` found pixels: those pixels of the technique's V (before "
             "the attached-shadow mask) by kind, an 8-bit RGB PNG: red NaN or infinite, blue "
             "below 0, yellow above 1, black the rest; written even with `run --no-images`; "
             "absent from older records"});
    v.field("masks", &I::masks,
            {"",
             "by region of `metrics.visibility`: an 8-bit PNG, 255 where the region "
             "measured (\"Recomputing the errors\"); absent from older records",
             Presence::UnlessEmpty});
  }

  bool empty() const;
  // Takes every image `other` names (a job's record, the reference's).
  void add(const ImagesRecord& other);
};

struct JobRecord {
  static constexpr RecordDoc kSchema{"JobRecord", "the whole record"};

  int schema_version = kRecordSchemaVersion;
  std::string run_id, experiment;
  std::string config, config_hash;  // the config path as given; FNV-1a 64 of its bytes
  std::string job_id;
  std::string spec_hash;  // of `spec`: what a rerun compares to keep the record
  // The named settings that decide the job's numbers (run/job_identity.h),
  // so that a rerun can say which changed; absent from older records.
  std::optional<nlohmann::json> spec;
  std::string scene_variant, technique_variant, resolution;
  int width = 0, height = 0;
  SceneRecord scene;
  TechniqueRecord technique;
  std::string backend, gl_platform, gl_renderer, gl_version, timing_source;
  // The job's place in its config's plan (scene, resolution, technique
  // order); absent from older records.
  std::optional<std::int64_t> job_index;
  std::optional<std::string> shard;  // "K/N" when run with --shard (plan/shards.h)
  HostRecord host;                   // the machine, and its fingerprint (record/host_record.h)
  BuildRecord build;                 // the build, and its fingerprint
  // The `run` process that timed it (record/session_record.h); absent from
  // older records.
  std::optional<SessionRecord> session;

  JobStatus status = JobStatus::Ok;
  std::optional<std::string> reason;  // why skipped or failed
  std::optional<std::string> started_at;
  std::optional<std::string> finished_at;
  std::optional<double> duration_s;  // jobs that rendered
  // Where duration_s went, and the part of it that is neither the frames
  // nor the stability block's (record/phases_record.h); jobs that rendered.
  std::optional<PhasesRecord> phases_s;
  std::optional<double> overhead_s;

  // What the job got to before it finished or failed.
  std::optional<ReferenceRecord> reference;
  std::optional<TimingRecord> timing;
  std::optional<VisibilityCheckRecord> visibility_check;
  std::optional<MetricsRecord> metrics;
  std::optional<SecondReferenceRecord> second_reference;  // reference.second_method
  std::optional<StabilityRecord> stability;               // the "stability" block
  std::optional<ClassesRecord> classes;  // lit/penumbra/umbra against the reference
  // A failed job's measurements (above, and technique.gpu_bytes), moved here
  // by set_aside_failed_measurements().
  std::optional<PartialRecord> partial;
  std::vector<std::string> warnings;  // written only when there are some
  // A job whose process died (crash, timeout, out of memory): the last lines
  // that process wrote to stderr. Written only when there are some.
  std::vector<std::string> child_stderr;
  ImagesRecord images;  // written only when some image was

  template <class V>
  static void describe(V& v);

  nlohmann::json to_json() const;
  // Throws RecordError: at /schema_version for another version, else at the
  // first member that is missing or of the wrong type.
  static JobRecord from_json(const nlohmann::json& j);

  // A failed job carries no figures: moves its timing, technique.gpu_bytes,
  // metrics, second_reference and classes into `partial` (keeping what
  // `partial` already has). Nothing for a job that did not fail. The
  // executor calls it on a job that failed, from_json on every record, so
  // that failed records written before `partial` existed read the same way.
  void set_aside_failed_measurements();

  // The named metric ("visibility.all.rmse"), when the record has metrics.
  std::optional<double> metric(const MetricPath& path) const;
};

template <class V>
void JobRecord::describe(V& v) {
  using J = JobRecord;
  v.field("schema_version", &J::schema_version,
          {"", "1; a reader refuses any other, naming the file and the version"});
  v.field("run_id", &J::run_id, {"", "the run"});
  v.field("experiment", &J::experiment, {"", "the experiment's name"});
  v.field("config", &J::config, {"", "the config path as given"});
  v.field("config_hash", &J::config_hash, {"", "FNV-1a 64 of its bytes"});
  v.field("job_id", &J::job_id,
          {"", "`<scene variant>__<WxH>__<technique variant>`, file-name safe"});
  v.field("spec_hash", &J::spec_hash, {"", "the hash of `spec` that resuming compares"});
  v.field("spec", &J::spec,
          {"",
           "the job's settings as named fields (above); absent from older records, which "
           "rerun"});
  v.field("scene_variant", &J::scene_variant, {"", "what ran"});
  v.field("technique_variant", &J::technique_variant, {"", "what ran"});
  v.field("resolution", &J::resolution, {"", "`<W>x<H>`"});
  v.field("width", &J::width, {"px", "the frame's width: the resolution's W"});
  v.field("height", &J::height, {"px", "the frame's height: the resolution's H"});
  v.field("scene", &J::scene, {"", "the scene"});
  v.field("technique", &J::technique, {"", "the technique"});
  v.field("backend", &J::backend, {"", "`osmesa` or `egl`"});
  v.field("gl_platform", &J::gl_platform, {"", "`osmesa`, `egl-device` or `egl-surfaceless`"});
  v.field("gl_renderer", &J::gl_renderer, {"", "the driver's string"});
  v.field("gl_version", &J::gl_version, {"", "the driver's string"});
  v.field("timing_source", &J::timing_source,
          {"",
           "how every bracket in `timing` was timed: `cpu_glfinish`, `gl_timestamp_query` "
           "or (older GPU records) `gl_timer_query` (below)"});
  v.field("job_index", &J::job_index,
          {"",
           "the job's place in its config's plan (scene variants, then resolutions, then "
           "technique variants, from 0); absent from older records"});
  v.field("shard", &J::shard, {"", "`\"K/N\"` when the job ran under `run --shard K/N`"});
  v.field("host", &J::host, {"", "the machine that timed the job"});
  v.field("build", &J::build, {"", "the build"});
  v.field("session", &J::session,
          {"", "the `run` process that timed the job; absent from older records"});
  v.custom(
      "status", "string", {"", "`ok`, `skipped` or `failed`"},
      [](const J& r) { return std::optional<nlohmann::json>(to_string(r.status)); },
      [](J& r, const Fields& f) { r.status = status_from(f); });
  v.field("reason", &J::reason,
          {"",
           "why skipped (the scene does not fit the technique) or failed (the error), on "
           "one line; a longer message or one of several lines is cut and names "
           "`jobs/<job_id>/failure.txt`, which holds it whole"});
  v.field("started_at", &J::started_at, {"", "UTC ISO 8601"});
  v.field("finished_at", &J::finished_at, {"", "UTC ISO 8601"});
  v.field("duration_s", &J::duration_s,
          {"s",
           "wall time of a job that rendered (warm-up, timed frames, read-back, metrics, "
           "images)"});
  v.field("phases_s", &J::phases_s, {"s", "where `duration_s` went"});
  v.field("overhead_s", &J::overhead_s,
          {"s",
           "`duration_s` − `phases_s.frames` − `phases_s.stability`: what the harness "
           "spent besides the frames and measurements asked for"});
  v.field("reference", &J::reference, {"", "the reference"});
  v.field("timing", &J::timing, {"", "the frames' times"});
  v.field("visibility_check", &J::visibility_check, {"", "V's range"});
  v.field("metrics", &J::metrics, {"", "the errors"});
  v.field("second_reference", &J::second_reference, {"", "with config `reference.second_method`"});
  v.field("stability", &J::stability,
          {"", "with a config `stability` block, for a job that was not broken"});
  v.field("classes", &J::classes, {"", "every measured job; absent from older records"});
  v.field("partial", &J::partial,
          {"",
           "a failed job's measurements, in place of `timing`, `technique.gpu_bytes`, "
           "`metrics`, `second_reference` and `classes`, which a failed record lacks"});
  v.field("warnings", &J::warnings,
          {"",
           "e.g. a reference whose penumbra noise is over half the technique's penumbra "
           "RMSE",
           Presence::UnlessEmpty});
  v.field("child_stderr", &J::child_stderr,
          {"", "when the job's process died under it: the last 20 lines it wrote to stderr",
           Presence::UnlessEmpty});
  v.field("images", &J::images, {"", "the images written", Presence::UnlessEmpty});
}

}  // namespace sb::record
