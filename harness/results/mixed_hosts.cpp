#include "results/mixed_hosts.h"

#include <set>

namespace sb::results {

using record::JobRecord;
using record::JobStatus;

std::string host_label(const JobRecord& r) {
  std::string label = r.host.name.value_or("?");
  if (r.host.cpu && !r.host.cpu->model.empty()) label += " (" + r.host.cpu->model + ")";
  return label + ", " + r.gl_renderer;
}

std::vector<std::string> distinct_hosts(const std::vector<JobRecord>& records) {
  std::vector<std::string> labels;
  std::set<std::string> seen;
  for (const JobRecord& r : records) {
    if (r.status != JobStatus::Ok) continue;  // no timings to mix
    const std::string key = r.host.fingerprint.value_or(host_label(r)) + "|" + r.gl_renderer;
    if (seen.insert(key).second) labels.push_back(host_label(r));
  }
  return labels;
}

}  // namespace sb::results
