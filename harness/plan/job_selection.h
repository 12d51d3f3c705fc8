#pragma once
// `run --only PATTERN` and `plan --only PATTERN`: the jobs whose id matches
// one of the patterns, globs as a shell reads them (fnmatch(3): `*`, `?`,
// `[...]`). A job's id is core::job_id: its scene variant, resolution and
// technique variant, each made file-safe ('/' -> "--", ',' -> '+'), joined
// by "__": sphere_grid__640x480__pcf_box--k=3+size=1024. It names the job's
// record (records/<id>.json) and image folder (jobs/<id>/).
#include <string>
#include <vector>

#include "plan/plan.h"

namespace sb::plan {

class JobSelection {
 public:
  JobSelection() = default;  // every job
  explicit JobSelection(std::vector<std::string> patterns) : patterns_(std::move(patterns)) {}

  bool all() const { return patterns_.empty(); }
  bool selects(const std::string& job_id) const;
  const std::vector<std::string>& patterns() const { return patterns_; }

  // Throws core::InputError (exit 2) naming the first pattern that matches
  // none of `plan`'s jobs, with a few of their ids: a mistyped pattern would
  // otherwise run nothing and succeed.
  void check(const Plan& plan) const;

 private:
  std::vector<std::string> patterns_;
};

// `plan --only`: how many of the plan's jobs the selection takes, then each
// one's outcome, id and technique variant.
std::string describe_selection(const config::Experiment& e, const Plan& plan,
                               const JobSelection& selection);

}  // namespace sb::plan
