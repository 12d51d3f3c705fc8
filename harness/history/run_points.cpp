#include "history/run_points.h"

#include <cmath>
#include <nlohmann/json.hpp>

namespace sb::history {

using record::JobRecord;
using record::JobStatus;

namespace {

// Every finite number under `j`, by its dotted path below `prefix`.
void add_numbers(const nlohmann::json& j, const std::string& prefix,
                 std::vector<std::pair<std::string, double>>& out) {
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) {
      std::string path = prefix;
      path += '.';
      path += key;
      add_numbers(value, path, out);
    }
  } else if (j.is_number()) {
    const double v = j.get<double>();
    if (std::isfinite(v)) out.emplace_back(prefix, v);
  }
}

void add_if_finite(const std::string& quantity, double v,
                   std::vector<std::pair<std::string, double>>& out) {
  if (std::isfinite(v)) out.emplace_back(quantity, v);
}

}  // namespace

std::string series_name(const std::string& scene_variant, const std::string& resolution,
                        const std::string& technique_variant) {
  return scene_variant + " @ " + resolution + " / " + technique_variant;
}

std::vector<JobPoints> run_points(const std::vector<JobRecord>& records) {
  std::vector<JobPoints> out;
  out.reserve(records.size());
  for (const JobRecord& r : records) {
    JobPoints p;
    p.job_id = r.job_id;
    p.scene_variant = r.scene_variant;
    p.resolution = r.resolution;
    p.technique_variant = r.technique_variant;
    p.series = series_name(r.scene_variant, r.resolution, r.technique_variant);
    p.status = record::to_string(r.status);
    p.reason = r.reason.value_or("");
    p.host_fingerprint = r.host.fingerprint.value_or("");
    p.build_fingerprint = r.build.fingerprint.value_or("");
    if (r.status == JobStatus::Ok && r.timing) {
      const record::TimingRecord& t = *r.timing;
      if (t.control && t.control->frame_ratio.count > 0)
        add_if_finite("time.frame_ratio", t.control->frame_ratio.median, p.values);
      if (t.frame.count > 0) add_if_finite("time.frame_ms", t.frame.median, p.values);
      if (t.technique.count > 0) add_if_finite("time.technique_ms", t.technique.median, p.values);
    }
    if (r.status == JobStatus::Ok && r.metrics)
      add_numbers(r.metrics->to_json(), "metrics", p.values);
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace sb::history
