#include "results/merge.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string_view>
#include <type_traits>

#include "config/json_file.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/folder_file.h"
#include "plan/plan_json.h"
#include "record/job_record.h"
#include "results/mixed_hosts.h"
#include "results/report.h"
#include "store/results_store.h"
#include "store/run_lock.h"

namespace sb::results {

using core::InputError;
using core::write_file_atomically;
using plan::read_plan_text;
using record::ImagesRecord;
using record::JobRecord;
using record::plan_difference;
using record::PlannedJobRecord;
using record::PlanRecord;
using store::read_job_records;
using store::ResultsStore;
using store::RunFolderLock;

namespace fs = std::filesystem;

namespace {

// An image merge copies is read whole into memory first.
constexpr size_t kMaxImageBytes = size_t(1) << 32;

// The shards of one config ran one plan and each kept it as plan.json: the
// merged folder keeps it when every folder has one and they plan the same
// jobs the same way (the config may have been named by different paths:
// the first folder's file is kept). Otherwise a warning says why there is
// none.
struct ShardsPlan {
  std::optional<PlanRecord> plan;
  std::string text;  // the first folder's plan.json, as the run wrote it
};

ShardsPlan the_shards_plan(const std::vector<std::string>& dirs,
                           std::vector<std::string>& warnings) {
  ShardsPlan out;
  std::string first_dir;
  for (const std::string& dir : dirs) {
    const fs::path file = fs::path(dir) / "plan.json";
    const std::optional<core::FolderFile> in = core::open_in_folder(dir, "plan.json");
    if (!in) {
      warnings.push_back(dir +
                         " has no plan.json (written by a build before runs kept their "
                         "plan): the merged folder has none, and which planned jobs are "
                         "missing is not checked");
      return {};
    }
    std::string text = in->read_all(config::JsonLimits{}.max_bytes);
    PlanRecord plan = read_plan_text(text, file.string());
    if (!out.plan) {
      out.text = std::move(text);
      out.plan = std::move(plan);
      first_dir = dir;
    } else if (const std::string d = plan_difference(*out.plan, plan); !d.empty()) {
      std::string why = "the shards' plans differ: in " + first_dir;
      why += ", " + d;
      why += " in " + dir;
      why += "; the merged folder keeps no plan.json";
      warnings.push_back(std::move(why));
      return {};
    }
  }
  return out;
}

// The planned jobs no folder recorded, said per shard.
void warn_of_missing_jobs(const PlanRecord& plan, const std::map<std::string, std::string>& where,
                          MergeSummary& summary) {
  std::map<int, std::pair<size_t, size_t>> per_shard;  // shard -> (missing, planned)
  for (const PlannedJobRecord& j : plan.jobs) {
    auto& [missing, planned] = per_shard[j.shard];
    ++planned;
    if (where.count(j.id) == 0) {
      ++missing;
      summary.missing_jobs.push_back(j.id);
    }
  }
  if (summary.missing_jobs.empty()) return;
  std::string shards;
  for (const auto& [shard, n] : per_shard)
    if (n.first > 0)
      shards += std::string(shards.empty() ? "" : ", ") + "shard " + std::to_string(shard) +
                " of " + std::to_string(plan.shard_count) + ": " + std::to_string(n.first) +
                " of its " + std::to_string(n.second);
  summary.warnings.push_back(std::to_string(summary.missing_jobs.size()) + " of the plan's " +
                             std::to_string(plan.jobs.size()) +
                             (summary.missing_jobs.size() == 1 ? " jobs has" : " jobs have") +
                             " no record in these folders (" + shards +
                             "): the merged results are incomplete");
}

// The marker of a folder merge made (written first into OUT): merge writes
// only into a new or empty folder or one that holds it.
constexpr const char* kMergeMarkerFile = ".shadowbench-merge";

// Throws InputError naming what stops merge from writing into `out`: a file
// or folder there that no merge made. merge replaces plan.json, summary.md,
// results.csv and the images it copies: they must be its own.
void check_merge_out(const std::string& out) {
  const fs::file_status folder = fs::symlink_status(out);
  if (folder.type() == fs::file_type::not_found) return;
  const std::string why =
      "is not merge's: merge writes into a new or empty folder, or one an earlier merge made "
      "(its marker " +
      std::string(kMergeMarkerFile) + "), and keeps anything else; choose another folder";
  if (folder.type() != fs::file_type::directory) throw InputError(out, "", why);
  if (fs::symlink_status(fs::path(out) / kMergeMarkerFile).type() == fs::file_type::regular) return;
  for (const fs::directory_entry& e : fs::directory_iterator(out))
    throw InputError(e.path().string(), "", why);
}

// What file_safe() and job_id() write: letters, digits, . _ - = + ~, and no
// leading '.'.
bool file_name_safe(const std::string& id) {
  if (id.empty() || id[0] == '.') return false;
  return std::all_of(id.begin(), id.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) ||
           std::string_view("._-=+~").find(c) != std::string_view::npos;
  });
}

// Every path an images record names, from its description (so that an image
// added to the record is merged without a list here to keep up): each
// optional path, and each region's mask.
class ImagePaths {
 public:
  explicit ImagePaths(const ImagesRecord& im) : im_(im) {}
  std::vector<std::string> paths;

  template <class M>
  void field(const char* /*key*/, M ImagesRecord::*member, const record::FieldInfo& /*info*/ = {}) {
    if constexpr (std::is_same_v<M, std::optional<std::string>>) {
      if (im_.*member) paths.push_back(*(im_.*member));
    } else if constexpr (std::is_same_v<M, std::map<std::string, std::string>>) {
      for (const auto& [region, path] : im_.*member) paths.push_back(path);
    }
  }

 private:
  const ImagesRecord& im_;
};

std::vector<std::string> image_paths(const ImagesRecord& im) {
  ImagePaths collect(im);
  ImagesRecord::describe(collect);
  return std::move(collect.paths);
}

}  // namespace

MergeSummary merge_runs(const std::string& out, const std::vector<std::string>& dirs,
                        const MergeOptions& options) {
  struct Source {
    JobRecord record;
    std::string dir;
  };
  std::vector<Source> all;
  std::map<std::string, std::string> where;  // job id -> its folder
  for (const std::string& dir : dirs) {
    const std::string jsonl = (fs::path(dir) / "results.jsonl").string();
    if (fs::weakly_canonical(fs::absolute(dir)) == fs::weakly_canonical(fs::absolute(out)))
      throw InputError(dir, "", "is the folder merged into: merge into a new folder");
    std::vector<JobRecord> records = read_job_records(dir);
    if (records.empty()) throw InputError(jsonl, "", "holds no records");
    for (JobRecord& r : records) {
      if (!all.empty() && r.config_hash != all.front().record.config_hash)
        throw InputError(jsonl, "job " + r.job_id,
                         "ran config " + r.config + " (hash " + r.config_hash + "), not " +
                             all.front().record.config + " (hash " +
                             all.front().record.config_hash + ") as " + all.front().dir +
                             " did: merge joins the shards of one config");
      // The id names its record file: a crafted one must not point elsewhere.
      if (!file_name_safe(r.job_id))
        throw InputError(jsonl, "job " + r.job_id, "is not a job id shadowbench writes");
      if (const auto [it, fresh] = where.emplace(r.job_id, dir); !fresh)
        throw InputError(jsonl, "job " + r.job_id,
                         "is also in " + it->second +
                             ": two folders ran the same job (overlapping shards, or one "
                             "folder given twice)");
      // Each image inside its run folder, a regular file not reached through
      // a symbolic link (core/folder_file.h), before anything is written.
      for (const std::string& rel : image_paths(r.images)) {
        if (const std::string why = core::folder_path_problem(rel); !why.empty()) {
          std::string what = "names the image '" + rel;
          what += "', outside its run folder: the path " + why;
          throw InputError(jsonl, "job " + r.job_id, what);
        }
        (void)core::open_in_folder(dir, rel);
      }
      all.push_back({std::move(r), dir});
    }
  }

  // One run's order: the plan's, where the records know it.
  std::stable_sort(all.begin(), all.end(), [](const Source& a, const Source& b) {
    const auto ia = a.record.job_index.value_or(INT64_MAX);
    const auto ib = b.record.job_index.value_or(INT64_MAX);
    return ia != ib ? ia < ib : a.record.job_id < b.record.job_id;
  });
  std::vector<JobRecord> records;
  std::vector<std::string> order;
  records.reserve(all.size());
  order.reserve(all.size());
  for (const Source& s : all) {
    records.push_back(s.record);
    order.push_back(s.record.job_id);
  }
  MergeSummary summary;
  const ShardsPlan plan = the_shards_plan(dirs, summary.warnings);
  summary.hosts = distinct_hosts(records);
  if (summary.hosts.size() > 1 && !options.allow_mixed_hosts) {
    std::string list;
    for (const std::string& h : summary.hosts) list += "\n  " + h;
    throw InputError(dirs.front(), "",
                     "the folders' timings come from " + std::to_string(summary.hosts.size()) +
                         " hosts or GL renderers, which one comparison must not mix:" + list +
                         "\n(merge --allow-mixed-hosts merges them anyway; the report then "
                         "marks them)");
  }

  check_merge_out(out);
  fs::create_directories(out);
  write_file_atomically((fs::path(out) / kMergeMarkerFile).string(),
                        "Written by shadowbench merge: a later merge may write into this folder.\n",
                        "merge: ");
  const RunFolderLock lock(out);
  if (fs::exists(fs::path(out) / "records") && !fs::is_empty(fs::path(out) / "records"))
    throw InputError(out, "", "already holds records: merge into a new or empty folder");
  ResultsStore store(out);
  store.set_order(order);
  std::set<std::string> copied;
  for (const Source& s : all) {
    for (const std::string& rel : image_paths(s.record.images)) {
      // The reference's images are shared by a group's jobs, and equal in
      // every shard that rendered the group: copied once.
      if (!copied.insert(rel).second) continue;
      // Read inside the folder, as a regular file: a link is never followed.
      const std::optional<core::FolderFile> from = core::open_in_folder(s.dir, rel);
      if (!from) continue;  // written with --no-images, or removed
      const fs::path to = fs::path(out) / rel;
      core::make_own_folder(out, fs::path(rel).parent_path().string(), "merge: ");
      write_file_atomically(to.string(), from->read_all(kMaxImageBytes), "merge: ");
      ++summary.images;
    }
  }
  if (plan.plan) {
    write_file_atomically((fs::path(out) / "plan.json").string(), plan.text, "merge: ");
    warn_of_missing_jobs(*plan.plan, where, summary);
  }
  store.put_all(records);
  summary.records = records.size();
  write_reports(out, store.records(),
                records.front().experiment + " (merged from " + std::to_string(dirs.size()) +
                    " run folders)");
  return summary;
}

}  // namespace sb::results
