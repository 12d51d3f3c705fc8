#include "results/bencher_json.h"

#include <cmath>

#include "core/atomic_file.h"
#include "results/compare.h"
#include "store/results_store.h"

namespace sb::results {

using core::write_file_atomically;
using record::JobRecord;
using record::JobStatus;
using record::Series;
using store::json_text;

using nlohmann::json;

json make_bencher_json(const std::vector<JobRecord>& records) {
  json out = json::object();
  for (const auto& r : records) {
    if (r.status != JobStatus::Ok) continue;
    json b = json::object();
    if (r.timing && std::isfinite(r.timing->frame.median)) {
      constexpr double kNsPerMs = 1e6;
      const Series& f = r.timing->frame;
      json latency = {{"value", f.median * kNsPerMs}};
      if (std::isfinite(f.p10)) latency["lower_value"] = f.p10 * kNsPerMs;
      if (std::isfinite(f.p90)) latency["upper_value"] = f.p90 * kNsPerMs;
      b["latency"] = std::move(latency);
    }
    const std::pair<const char*, const char*> errors[] = {
        {"rmse", "visibility.all.rmse"}, {"penumbra-rmse", "visibility.penumbra.rmse"}};
    for (const auto& [slug, path] : errors) {
      const auto v = metric_value(r, path);
      if (v && std::isfinite(*v)) b[slug] = {{"value", *v}};
    }
    if (!b.empty()) out[r.job_id] = std::move(b);
  }
  return out;
}

void write_bencher_json(const std::string& path, const std::vector<JobRecord>& records) {
  write_file_atomically(path, json_text(make_bencher_json(records), 2) + "\n");
}

}  // namespace sb::results
