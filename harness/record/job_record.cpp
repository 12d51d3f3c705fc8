#include "record/job_record.h"

namespace sb {

using json = nlohmann::json;

namespace {

// The image paths of a record, by key, in one list for both directions.
struct ImageKey {
  const char* key;
  std::optional<std::string> ImagesRecord::*path;
};

const ImageKey kImageKeys[] = {
    {"visibility", &ImagesRecord::visibility},
    {"shaded", &ImagesRecord::shaded},
    {"error_heatmap", &ImagesRecord::error_heatmap},
    {"reference_visibility", &ImagesRecord::reference_visibility},
    {"reference_std_error", &ImagesRecord::reference_std_error},
    {"reference_shaded", &ImagesRecord::reference_shaded},
    {"gbuffer_positions", &ImagesRecord::gbuffer_positions},
    {"gbuffer_normals", &ImagesRecord::gbuffer_normals},
};

JobStatus status_from(const Fields& f) {
  const std::string s = f.get<std::string>("status");
  for (const JobStatus st : {JobStatus::Ok, JobStatus::Skipped, JobStatus::Failed})
    if (s == to_string(st)) return st;
  f.fail("status", "expected \"ok\", \"skipped\" or \"failed\", found \"" + s + "\"");
}

void check_schema_version(const json& j) {
  const Fields f(j, "");
  if (!f.has("schema_version"))
    f.fail("schema_version", "missing: this is not a shadowbench job record");
  const json& v = j.at("schema_version");
  if (!v.is_number_integer() || v.get<std::int64_t>() != kRecordSchemaVersion)
    f.fail("schema_version", "the record has schema_version " + v.dump() +
                                 "; this shadowbench reads schema_version " +
                                 std::to_string(kRecordSchemaVersion) + " (docs/results.md)");
}

}  // namespace

const char* to_string(JobStatus s) {
  switch (s) {
    case JobStatus::Ok:
      return "ok";
    case JobStatus::Skipped:
      return "skipped";
    case JobStatus::Failed:
      break;
  }
  return "failed";
}

bool ImagesRecord::empty() const {
  for (const auto& k : kImageKeys)
    if ((this->*k.path).has_value()) return false;
  return masks.empty() && !error_heatmap_full_scale.has_value();
}

void ImagesRecord::add(const ImagesRecord& other) {
  for (const auto& k : kImageKeys)
    if ((other.*k.path).has_value()) this->*k.path = other.*k.path;
  if (other.error_heatmap_full_scale) error_heatmap_full_scale = other.error_heatmap_full_scale;
  for (const auto& [region, path] : other.masks) masks[region] = path;
}

json JobRecord::to_json() const {
  json r;
  r["schema_version"] = schema_version;
  r["run_id"] = run_id;
  r["config"] = config;
  r["config_hash"] = config_hash;
  r["experiment"] = experiment;
  r["job_id"] = job_id;
  r["spec_hash"] = spec_hash;
  if (spec) r["spec"] = *spec;
  r["scene_variant"] = scene_variant;
  r["scene"] = scene.to_json();
  r["technique_variant"] = technique_variant;
  r["technique"] = technique.to_json();
  r["resolution"] = resolution;
  r["width"] = width;
  r["height"] = height;
  r["backend"] = backend;
  r["gl_platform"] = gl_platform;
  r["gl_renderer"] = gl_renderer;
  r["gl_version"] = gl_version;
  r["timing_source"] = timing_source;
  if (job_index) r["job_index"] = *job_index;
  if (shard) r["shard"] = *shard;
  r["host"] = host.to_json();
  r["build"] = build.to_json();
  r["status"] = to_string(status);
  if (reason) r["reason"] = *reason;
  if (started_at) r["started_at"] = *started_at;
  if (finished_at) r["finished_at"] = *finished_at;
  if (duration_s) r["duration_s"] = json_number(*duration_s);
  if (phases_s) r["phases_s"] = phases_s->to_json();
  if (overhead_s) r["overhead_s"] = json_number(*overhead_s);
  if (reference) r["reference"] = reference->to_json();
  if (timing) r["timing"] = timing->to_json();
  if (visibility_check)
    r["visibility_check"] = {{"nonfinite", visibility_check->nonfinite},
                             {"below_0", visibility_check->below_0},
                             {"above_1", visibility_check->above_1},
                             {"tolerance", json_number(visibility_check->tolerance)}};
  if (metrics) r["metrics"] = metrics->to_json();
  if (second_reference) r["second_reference"] = second_reference->to_json();
  if (stability) r["stability"] = stability->to_json();
  if (classes) r["classes"] = classes->to_json();
  if (!warnings.empty()) r["warnings"] = warnings;
  if (!child_stderr.empty()) r["child_stderr"] = child_stderr;
  if (!images.empty()) {
    json& im = r["images"];
    for (const auto& k : kImageKeys)
      if (const auto& path = images.*k.path) im[k.key] = *path;
    if (images.error_heatmap_full_scale)
      im["error_heatmap_full_scale"] = json_number(*images.error_heatmap_full_scale);
    if (!images.masks.empty()) im["masks"] = images.masks;
  }
  return r;
}

JobRecord JobRecord::from_json(const json& j) {
  check_schema_version(j);
  const Fields f(j, "");
  JobRecord r;
  r.schema_version = kRecordSchemaVersion;
  r.run_id = f.get<std::string>("run_id");
  r.experiment = f.get<std::string>("experiment");
  r.config = f.get<std::string>("config");
  r.config_hash = f.get<std::string>("config_hash");
  r.job_id = f.get<std::string>("job_id");
  r.spec_hash = f.get<std::string>("spec_hash");
  if (f.has("spec")) r.spec = f.get<nlohmann::json>("spec");
  r.scene_variant = f.get<std::string>("scene_variant");
  r.technique_variant = f.get<std::string>("technique_variant");
  r.resolution = f.get<std::string>("resolution");
  r.width = f.get<int>("width");
  r.height = f.get<int>("height");
  r.scene = SceneRecord::from_json(f.object("scene"));
  r.technique = TechniqueRecord::from_json(f.object("technique"));
  r.backend = f.get<std::string>("backend");
  r.gl_platform = f.get<std::string>("gl_platform");
  r.gl_renderer = f.get<std::string>("gl_renderer");
  r.gl_version = f.get<std::string>("gl_version");
  r.timing_source = f.get<std::string>("timing_source");
  r.job_index = f.find<std::int64_t>("job_index");
  r.shard = f.find<std::string>("shard");
  r.host = HostRecord::from_json(f.object("host"));
  r.build = BuildRecord::from_json(f.object("build"));

  r.status = status_from(f);
  r.reason = f.find<std::string>("reason");
  r.started_at = f.find<std::string>("started_at");
  r.finished_at = f.find<std::string>("finished_at");
  r.duration_s = f.find<double>("duration_s");
  if (const auto p = f.find_object("phases_s")) r.phases_s = PhasesRecord::from_json(*p);
  r.overhead_s = f.find<double>("overhead_s");
  if (const auto ref = f.find_object("reference")) r.reference = ReferenceRecord::from_json(*ref);
  if (const auto t = f.find_object("timing")) r.timing = TimingRecord::from_json(*t);
  if (const auto c = f.find_object("visibility_check")) {
    VisibilityCheckRecord v;
    v.nonfinite = c->get<std::int64_t>("nonfinite");
    v.below_0 = c->get<std::int64_t>("below_0");
    v.above_1 = c->get<std::int64_t>("above_1");
    v.tolerance = c->get<double>("tolerance");
    r.visibility_check = v;
  }
  if (const auto m = f.find_object("metrics")) r.metrics = MetricsRecord::from_json(*m);
  if (const auto s = f.find_object("second_reference"))
    r.second_reference = SecondReferenceRecord::from_json(*s);
  if (const auto s = f.find_object("stability")) r.stability = StabilityRecord::from_json(*s);
  if (const auto c = f.find_object("classes")) r.classes = ClassesRecord::from_json(*c);
  if (f.has("warnings")) r.warnings = f.get<std::vector<std::string>>("warnings");
  if (f.has("child_stderr")) r.child_stderr = f.get<std::vector<std::string>>("child_stderr");
  if (const auto im = f.find_object("images")) {
    for (const auto& k : kImageKeys) r.images.*k.path = im->find<std::string>(k.key);
    r.images.error_heatmap_full_scale = im->find<double>("error_heatmap_full_scale");
    if (const auto masks = im->find_object("masks"))
      for (const std::string& region : masks->keys())
        r.images.masks[region] = masks->get<std::string>(region);
  }
  return r;
}

std::optional<double> JobRecord::metric(const MetricPath& path) const {
  if (!metrics) return std::nullopt;
  return path.of(*metrics);
}

}  // namespace sb
