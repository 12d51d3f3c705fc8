#pragma once
// Which machines timed a run folder's jobs. One folder normally has one;
// `merge --allow-mixed-hosts` can make one with several, and then every
// report says so: frame times are only comparable within one host.
#include <optional>
#include <string>
#include <vector>

#include "record/job_record.h"
#include "results/banner.h"

namespace sb::results {

// "name (cpu), renderer".
std::string host_label(const record::JobRecord& r);

// The hosts that timed the ok jobs, told apart by host fingerprint and GL
// renderer, as host labels in order of first appearance.
std::vector<std::string> distinct_hosts(const std::vector<record::JobRecord>& records);

// "Mixed hosts" and the host labels, when there is more than one.
std::optional<Banner> mixed_hosts_banner(const std::vector<record::JobRecord>& records);

}  // namespace sb::results
