#include "results/store.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

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

nlohmann::json json_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return v;
}

ResultsStore::ResultsStore(std::string run_dir) : dir_(std::move(run_dir)) {
  fs::create_directories(fs::path(dir_) / "records");
  for (const auto& e : fs::directory_iterator(fs::path(dir_) / "records")) {
    if (e.path().extension() != ".json") continue;
    std::ifstream in(e.path());
    try {
      nlohmann::json r = nlohmann::json::parse(in);
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
                        record.dump(2) + "\n");
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
  for (const auto& r : records()) text += r.dump() + "\n";
  write_file_atomically((fs::path(dir_) / "results.jsonl").string(), text);
}

std::vector<nlohmann::json> read_run_records(const std::string& run_dir) {
  std::vector<nlohmann::json> out;
  const fs::path jsonl = fs::path(run_dir) / "results.jsonl";
  std::ifstream in(jsonl);
  if (!in) throw InputError(jsonl.string(), "", "cannot open the results file");
  std::string line;
  size_t n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty()) continue;
    try {
      out.push_back(nlohmann::json::parse(line));
    } catch (const nlohmann::json::parse_error& e) {
      throw InputError(jsonl.string(), "line " + std::to_string(n),
                       std::string("invalid JSON: ") + e.what());
    }
  }
  return out;
}

}  // namespace sb
