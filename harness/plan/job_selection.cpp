#include "plan/job_selection.h"

#include <fnmatch.h>

#include <algorithm>

#include "core/bounded_text.h"
#include "core/error.h"

namespace sb::plan {

namespace {

constexpr size_t kIdsShown = 5;

bool matches(const std::string& pattern, const std::string& id) {
  return ::fnmatch(pattern.c_str(), id.c_str(), 0) == 0;
}

}  // namespace

bool JobSelection::selects(const std::string& job_id) const {
  return all() || std::any_of(patterns_.begin(), patterns_.end(),
                              [&](const std::string& p) { return matches(p, job_id); });
}

void JobSelection::check(const Plan& plan) const {
  for (const std::string& pattern : patterns_) {
    if (std::any_of(plan.jobs.begin(), plan.jobs.end(),
                    [&](const PlannedJob& j) { return matches(pattern, j.id); }))
      continue;
    std::string ids;
    for (size_t i = 0; i < plan.jobs.size() && i < kIdsShown; ++i)
      ids += (i == 0 ? "" : ", ") + plan.jobs[i].id;
    if (plan.jobs.size() > kIdsShown)
      ids += ", ... (" + std::to_string(plan.jobs.size()) + " in all)";
    throw core::InputError("--only", "",
                           core::quoted_text(pattern) + " selects no job; job ids look like: " +
                               ids + " (`shadowbench plan CONFIG --only '*'` lists them all)");
  }
}

std::string describe_selection(const config::Experiment& e, const Plan& plan,
                               const JobSelection& selection) {
  std::string list;
  size_t n = 0;
  for (const PlannedJob& j : plan.jobs) {
    if (!selection.selects(j.id)) continue;
    ++n;
    std::string status = to_string(j.outcome.status);
    status.resize(5, ' ');
    list +=
        "  " + status + j.id + "  (" + core::bounded_text(e.techniques[j.technique].name) + ")\n";
  }
  std::string patterns;
  for (const std::string& p : selection.patterns())
    patterns += (patterns.empty() ? "" : " ") + core::quoted_text(p);
  return "--only " + patterns + " selects " + std::to_string(n) + " of " +
         std::to_string(plan.jobs.size()) + " jobs:\n" + list;
}

}  // namespace sb::plan
