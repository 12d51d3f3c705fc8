#include "results/bencher_json.h"

#include <cmath>

#include "results/compare.h"
#include "results/store.h"

namespace sb {
namespace {

using nlohmann::json;

double number_or_nan(const json& o, const char* key) {
  if (o.is_object() && o.contains(key) && o[key].is_number()) return o[key].get<double>();
  return std::nan("");
}

}  // namespace

json make_bencher_json(const std::vector<json>& records) {
  json out = json::object();
  for (const auto& r : records) {
    if (r.value("status", "") != "ok") continue;
    json b = json::object();
    if (r.contains("timing") && r["timing"].is_object() && r["timing"].contains("frame")) {
      const json& f = r["timing"]["frame"];
      const double median = number_or_nan(f, "median_ms");
      if (std::isfinite(median)) {
        constexpr double kNsPerMs = 1e6;
        json latency = {{"value", median * kNsPerMs}};
        const double p10 = number_or_nan(f, "p10_ms"), p90 = number_or_nan(f, "p90_ms");
        if (std::isfinite(p10)) latency["lower_value"] = p10 * kNsPerMs;
        if (std::isfinite(p90)) latency["upper_value"] = p90 * kNsPerMs;
        b["latency"] = std::move(latency);
      }
    }
    const std::pair<const char*, const char*> errors[] = {
        {"rmse", "visibility.all.rmse"}, {"penumbra-rmse", "visibility.penumbra.rmse"}};
    for (const auto& [slug, path] : errors) {
      const auto v = metric_value(r, path);
      if (v && std::isfinite(*v)) b[slug] = {{"value", *v}};
    }
    if (!b.empty()) out[r.value("job_id", "")] = std::move(b);
  }
  return out;
}

void write_bencher_json(const std::string& path, const std::vector<json>& records) {
  write_file_atomically(path, json_text(make_bencher_json(records), 2) + "\n");
}

}  // namespace sb
