#include "results/store.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "config/json_file.h"
#include "core/error.h"

namespace sb {
namespace fs = std::filesystem;

void write_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) throw JobError("cannot write " + tmp);
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw JobError("cannot rename " + tmp + " to " + path + ": " + ec.message());
}

std::string json_text(const nlohmann::json& value, int indent) {
  return value.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

ResultsStore::ResultsStore(std::string run_dir) : dir_(std::move(run_dir)) {
  fs::create_directories(fs::path(dir_) / "records");
  for (const auto& e : fs::directory_iterator(fs::path(dir_) / "records")) {
    if (e.path().extension() != ".json") continue;
    try {
      nlohmann::json r = read_json_file(e.path().string());
      if (!r.contains("job_id") || !r["job_id"].is_string()) continue;
      // Key first: json's operator= takes its argument by value, and C++17
      // evaluates the right side first, which would empty `r` before the key is read.
      const std::string key = r["job_id"].get<std::string>();
      records_[key] = std::move(r);
    } catch (const std::exception&) {
      // A torn or foreign file: the job simply runs again.
    }
  }
}

const nlohmann::json* ResultsStore::finished(const std::string& job_id) const {
  auto it = records_.find(job_id);
  if (it == records_.end()) return nullptr;
  const std::string status = it->second.value("status", "");
  return status == "ok" || status == "skipped" ? &it->second : nullptr;
}

void ResultsStore::put(const std::string& job_id, const nlohmann::json& record) {
  write_file_atomically((fs::path(dir_) / "records" / (job_id + ".json")).string(),
                        json_text(record, 2) + "\n");
  records_[job_id] = record;
  rewrite_jsonl();
}

std::vector<nlohmann::json> ResultsStore::records() const {
  std::vector<nlohmann::json> out;
  std::set<std::string> seen;
  for (const auto& id : order_) {
    auto it = records_.find(id);
    if (it != records_.end() && seen.insert(id).second) out.push_back(it->second);
  }
  for (const auto& [id, r] : records_)
    if (seen.insert(id).second) out.push_back(r);
  return out;
}

void ResultsStore::rewrite_jsonl() const {
  std::string text;
  for (const auto& r : records()) text += json_text(r) + "\n";
  write_file_atomically((fs::path(dir_) / "results.jsonl").string(), text);
}

std::vector<nlohmann::json> read_run_records(const std::string& run_dir) {
  // Records are input like any other: someone else's run folder, or a
  // crafted one. Every line is parsed with the config's limits.
  std::vector<nlohmann::json> out;
  const fs::path jsonl = fs::path(run_dir) / "results.jsonl";
  const std::string text = read_input_file(jsonl.string(), size_t(1) << 30, "results file");
  size_t n = 0, begin = 0;
  while (begin < text.size()) {
    size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    ++n;
    if (end > begin)
      out.push_back(parse_json_text(text.substr(begin, end - begin), jsonl.string(), {}, n - 1));
    begin = end + 1;
  }
  return out;
}

}  // namespace sb
