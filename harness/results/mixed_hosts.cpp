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

std::optional<Banner> mixed_hosts_banner(const std::vector<JobRecord>& records) {
  std::vector<std::string> hosts = distinct_hosts(records);
  if (hosts.size() < 2) return std::nullopt;
  return Banner{"Mixed hosts",
                "these jobs were timed on " + std::to_string(hosts.size()) +
                    " hosts or GL renderers (merged with `--allow-mixed-hosts`); compare frame "
                    "times only between jobs of one host:",
                std::move(hosts)};
}

}  // namespace sb::results
