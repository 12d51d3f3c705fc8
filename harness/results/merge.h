#pragma once
// `shadowbench merge OUT DIR...`: the run folders of one config's shards
// (run --shard K/N, plan/shards.h) made into one run folder, as if one run
// had written it: every record, its images, results.jsonl in plan order
// (record job_index), and the reports.
//
// Refused, as bad input naming the folder: records of different configs, a
// job in two folders, and, unless allow_mixed_hosts, timings from different
// hosts or GL renderers (host fingerprint and gl_renderer), which one
// comparison must not mix. The report marks a folder that does mix them.
//
// The folders' plan.json files are read back (plan/plan_json.h): the merged
// folder keeps the plan when they agree, and merge warns of every planned
// job no folder recorded (a shard not given, or one that stopped early).
#include <string>
#include <vector>

namespace sb::results {

struct MergeOptions {
  bool allow_mixed_hosts = false;
};

struct MergeSummary {
  size_t records = 0;
  size_t images = 0;               // image files copied
  std::vector<std::string> hosts;  // "name (cpu), renderer", one per distinct host
  // Jobs of the shards' plan (plan.json) that no folder recorded, in plan
  // order; and what merge warns of: those, or why it kept no plan.json.
  std::vector<std::string> missing_jobs;
  std::vector<std::string> warnings;
};

// OUT must be new or hold no records. Throws InputError for the refusals
// above and for unreadable run folders.
MergeSummary merge_runs(const std::string& out, const std::vector<std::string>& dirs,
                        const MergeOptions& options);

}  // namespace sb::results
