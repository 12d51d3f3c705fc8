#include "store/results_store.h"

#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <set>

#include "config/json_file.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/folder_file.h"

namespace sb::store {

using config::parse_json_text;
using config::read_json_file;
using core::InputError;
using core::is_atomic_temp_name;
using core::write_file_atomically;
using record::JobRecord;
using record::JobStatus;
using record::RecordError;

namespace fs = std::filesystem;

namespace {

// Each non-empty line of run_dir/results.jsonl, parsed with the config's
// limits, with its line number. The file is read inside the folder
// (core/folder_file.h): a results.jsonl that links elsewhere is refused.
void for_each_line(const std::string& run_dir,
                   const std::function<void(const nlohmann::json&, size_t line)>& take) {
  const fs::path jsonl = fs::path(run_dir) / "results.jsonl";
  const std::optional<core::FolderFile> file = core::open_in_folder(run_dir, "results.jsonl");
  if (!file) throw InputError(jsonl.string(), "", "cannot open the results file: no such file");
  const std::string text = file->read_all(size_t(1) << 30);
  size_t n = 0, begin = 0;
  while (begin < text.size()) {
    size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    ++n;
    if (end > begin)
      take(parse_json_text(text.substr(begin, end - begin), jsonl.string(), {}, n - 1), n);
    begin = end + 1;
  }
}

}  // namespace

std::string json_text(const nlohmann::json& value, int indent) {
  return value.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

ResultsStore::ResultsStore(std::string run_dir) : dir_(std::move(run_dir)) {
  core::make_own_folder(dir_, "records");
  // What a writer killed between its write and its rename leaves behind.
  for (const fs::path& folder : {fs::path(dir_), fs::path(dir_) / "records"})
    for (const auto& e : fs::directory_iterator(folder))
      if (e.is_regular_file() && is_atomic_temp_name(e.path().filename().string()))
        fs::remove(e.path());
  for (const auto& e : fs::directory_iterator(fs::path(dir_) / "records")) {
    if (e.path().extension() != ".json") continue;
    const std::string file = e.path().string();
    try {
      JobRecord r = JobRecord::from_json(read_json_file(file));
      // A record under another job's name was copied or edited: not this job's.
      if (r.job_id + ".json" != e.path().filename().string()) {
        untrusted_.push_back(file + ": holds the record of job \"" + r.job_id + "\"");
        continue;
      }
      const nlohmann::json as_json = r.to_json();
      keep(std::move(r), as_json);
    } catch (const InputError& ex) {
      untrusted_.push_back(ex.what());  // names the file and the place
    } catch (const RecordError& ex) {
      untrusted_.push_back(file + (ex.pointer().empty() ? "" : ": at " + ex.pointer()) + ": " +
                           ex.problem());
    }
  }
}

const JobRecord* ResultsStore::finished(const std::string& job_id) const {
  auto it = records_.find(job_id);
  if (it == records_.end()) return nullptr;
  const JobStatus s = it->second.status;
  return s == JobStatus::Ok || s == JobStatus::Skipped ? &it->second : nullptr;
}

void ResultsStore::put(const JobRecord& record) { put_all({record}); }

void ResultsStore::put_all(const std::vector<JobRecord>& records) {
  for (const JobRecord& r : records) {
    const nlohmann::json j = r.to_json();
    write_file_atomically((fs::path(dir_) / "records" / (r.job_id + ".json")).string(),
                          json_text(j, 2) + "\n");
    keep(r, j);
  }
  rewrite_jsonl();
}

void ResultsStore::keep(JobRecord record, const nlohmann::json& as_json) {
  const std::string id = record.job_id;
  lines_[id] = json_text(as_json) + "\n";
  records_[id] = std::move(record);
}

std::vector<std::string> ResultsStore::ordered_ids() const {
  std::vector<std::string> out;
  std::set<std::string> seen;
  for (const auto& id : order_)
    if (records_.count(id) > 0 && seen.insert(id).second) out.push_back(id);
  for (const auto& [id, r] : records_)
    if (seen.insert(id).second) out.push_back(id);
  return out;
}

std::vector<JobRecord> ResultsStore::records() const {
  std::vector<JobRecord> out;
  for (const auto& id : ordered_ids()) out.push_back(records_.at(id));
  return out;
}

void ResultsStore::rewrite_index() const { rewrite_jsonl(); }

void ResultsStore::rewrite_jsonl() const {
  std::string text;
  for (const auto& id : ordered_ids()) text += lines_.at(id);
  write_file_atomically((fs::path(dir_) / "results.jsonl").string(), text);
}

std::vector<JobRecord> read_job_records(const std::string& run_dir) {
  std::vector<JobRecord> out;
  const std::string file = (fs::path(run_dir) / "results.jsonl").string();
  for_each_line(run_dir, [&](const nlohmann::json& j, size_t line) {
    try {
      out.push_back(JobRecord::from_json(j));
    } catch (const RecordError& e) {
      const std::string where = "line " + std::to_string(line);
      throw InputError(file, e.pointer().empty() ? where : where + " (" + e.pointer() + ")",
                       e.problem());
    }
  });
  return out;
}

std::vector<nlohmann::json> read_run_records(const std::string& run_dir) {
  std::vector<nlohmann::json> out;
  for_each_line(run_dir, [&](const nlohmann::json& j, size_t) { out.push_back(j); });
  return out;
}

}  // namespace sb::store
