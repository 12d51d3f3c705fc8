#pragma once
// The results store of one run directory:
//   records/<job_id>.json   one file per job, written atomically as it finishes
//   results.jsonl           every record, in plan order, rewritten atomically
// A rerun into the same directory keeps jobs whose record says "ok" or
// "skipped" and reruns the rest.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "record/job_record.h"

namespace sb::store {

class ResultsStore {
 public:
  // Reads the records/ of an earlier run of run_dir; a record that cannot be
  // read (torn, foreign, of another schema_version, another job's) is left
  // out and listed in untrusted(): its job runs again. Removes the temporary
  // files of writers that were killed before their rename.
  explicit ResultsStore(std::string run_dir);

  const std::string& dir() const { return dir_; }
  // A finished record from an earlier run of this directory, or null.
  const record::JobRecord* finished(const std::string& job_id) const;
  // Stores the record and rewrites results.jsonl (records ordered by `order`).
  void put(const record::JobRecord& record);
  // Stores each record, then rewrites results.jsonl once.
  void put_all(const std::vector<record::JobRecord>& records);
  void set_order(std::vector<std::string> job_ids) { order_ = std::move(job_ids); }
  // The record files left out, each "file: at /pointer: problem".
  const std::vector<std::string>& untrusted() const { return untrusted_; }
  // Rewrites results.jsonl from the records: a run killed between a record
  // and the index left them apart.
  void rewrite_index() const;
  std::vector<record::JobRecord> records() const;  // in plan order, then the rest

 private:
  std::vector<std::string> ordered_ids() const;  // records()'s order
  void keep(record::JobRecord record, const nlohmann::json& as_json);
  void rewrite_jsonl() const;
  std::string dir_;
  std::map<std::string, record::JobRecord> records_;
  // Each record's results.jsonl line, made once: a run's every record
  // rewrites the file, which would otherwise serialise every record again.
  std::map<std::string, std::string> lines_;
  std::vector<std::string> order_;
  std::vector<std::string> untrusted_;
};

// The records of a run directory's results.jsonl, for report, compare and
// the CI outputs. Run folders are input like any other: a line that is not
// JSON, or a record that does not follow the schema (record/job_record.h;
// another schema_version included), is an InputError naming the file, the
// line and the JSON pointer.
std::vector<record::JobRecord> read_job_records(const std::string& run_dir);
// The same lines as JSON, unread: for tests and tools that check the written
// schema itself.
std::vector<nlohmann::json> read_run_records(const std::string& run_dir);
// JSON text for output. Strings may hold bytes that are not UTF-8 (a file
// name, a glTF URI, a driver message): they are written as U+FFFD instead of
// making nlohmann throw and the run lose its records.
std::string json_text(const nlohmann::json& value, int indent = -1);

}  // namespace sb::store
