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
#include "record/fields.h"
#include "record/host_record.h"
#include "record/metrics_record.h"
#include "record/phases_record.h"
#include "record/reference_record.h"
#include "record/scene_record.h"
#include "record/second_reference_record.h"
#include "record/stability_record.h"
#include "record/timing_record.h"

namespace sb {

// The schema_version this build writes and reads.
inline constexpr int kRecordSchemaVersion = 1;

enum class JobStatus { Ok, Skipped, Failed };
const char* to_string(JobStatus s);  // "ok", "skipped", "failed"

// Pixels of the technique's visibility (before the attached-shadow mask)
// that are not finite or outside [0, 1] by more than the tolerance.
struct VisibilityCheckRecord {
  std::int64_t nonfinite = 0;
  std::int64_t below_0 = 0;
  std::int64_t above_1 = 0;
  double tolerance = 0;
};

// Paths relative to the run directory; each present only when written.
struct ImagesRecord {
  std::optional<std::string> visibility, shaded, error_heatmap;
  std::optional<double> error_heatmap_full_scale;
  std::optional<std::string> reference_visibility, reference_std_error, reference_shaded;
  std::optional<std::string> gbuffer_positions, gbuffer_normals;  // run --gbuffer
  // The pixels each metrics.visibility region measured, by region name (an
  // 8-bit PNG, 255 = measured): what recomputes the record's errors from
  // the files (docs/results.md "Recomputing the errors").
  std::map<std::string, std::string> masks;

  bool empty() const;
  // Takes every image `other` names (a job's record, the reference's).
  void add(const ImagesRecord& other);
};

struct JobRecord {
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
  std::vector<std::string> warnings;     // written only when there are some
  // A job whose process died (crash, timeout, out of memory): the last lines
  // that process wrote to stderr. Written only when there are some.
  std::vector<std::string> child_stderr;
  ImagesRecord images;  // written only when some image was

  nlohmann::json to_json() const;
  // Throws RecordError: at /schema_version for another version, else at the
  // first member that is missing or of the wrong type.
  static JobRecord from_json(const nlohmann::json& j);

  // The named metric ("visibility.all.rmse"), when the record has metrics.
  std::optional<double> metric(const MetricPath& path) const;
};

}  // namespace sb
