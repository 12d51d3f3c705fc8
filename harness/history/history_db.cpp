#include "history/history_db.h"

#include <sqlite3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>
#include <vector>

#include "core/error.h"
#include "history/run_points.h"
#include "record/job_record.h"
#include "results/store.h"

namespace sb::history {

namespace fs = std::filesystem;
using core::InputError;
using record::JobRecord;

namespace {

constexpr const char* kCreateTables = R"sql(
CREATE TABLE runs(
  run_key TEXT PRIMARY KEY,
  run_id TEXT NOT NULL,
  run_order INTEGER NOT NULL UNIQUE,
  commit_sha TEXT NOT NULL,
  added_at TEXT NOT NULL,
  started_at TEXT,
  experiment TEXT NOT NULL,
  config_hash TEXT NOT NULL,
  run_dir TEXT NOT NULL,
  host_fingerprint TEXT,
  build_fingerprint TEXT,
  record_schema_version INTEGER NOT NULL);
CREATE TABLE jobs(
  run_key TEXT NOT NULL REFERENCES runs(run_key) ON DELETE CASCADE,
  job_id TEXT NOT NULL,
  series TEXT NOT NULL,
  scene_variant TEXT NOT NULL,
  resolution TEXT NOT NULL,
  technique_variant TEXT NOT NULL,
  status TEXT NOT NULL,
  reason TEXT,
  host_fingerprint TEXT,
  build_fingerprint TEXT,
  PRIMARY KEY(run_key, job_id));
CREATE TABLE points(
  run_key TEXT NOT NULL,
  job_id TEXT NOT NULL,
  quantity TEXT NOT NULL,
  value REAL NOT NULL,
  PRIMARY KEY(run_key, job_id, quantity),
  FOREIGN KEY(run_key, job_id) REFERENCES jobs(run_key, job_id) ON DELETE CASCADE);
CREATE INDEX points_by_quantity ON points(quantity, run_key);
)sql";

std::string utc_now() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// The one value every record agrees on, or "" (also when none has one).
template <class Get>
std::string common_value(const std::vector<JobRecord>& records, Get get) {
  std::set<std::string> seen;
  for (const JobRecord& r : records) seen.insert(get(r));
  return seen.size() == 1 ? *seen.begin() : std::string();
}

}  // namespace

// One connection and the statements that need it; every failure is an
// InputError naming the file, since a history is a file the user gave.
struct HistoryDb::Connection {
  sqlite3* db = nullptr;
  std::string path;

  ~Connection() { sqlite3_close(db); }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(path, "", what + ": " + (db ? sqlite3_errmsg(db) : "cannot open"));
  }
  void exec(const char* sql) {
    char* message = nullptr;
    if (sqlite3_exec(db, sql, nullptr, nullptr, &message) != SQLITE_OK) {
      const std::string m = message ? message : "unknown error";
      sqlite3_free(message);
      throw InputError(path, "", m);
    }
  }
  std::int64_t scalar(const char* sql) {
    sqlite3_stmt* s = nullptr;
    if (sqlite3_prepare_v2(db, sql, -1, &s, nullptr) != SQLITE_OK) fail("cannot read it");
    std::int64_t v = 0;
    if (sqlite3_step(s) == SQLITE_ROW) v = sqlite3_column_int64(s, 0);
    sqlite3_finalize(s);
    return v;
  }
};

namespace {

// A prepared statement, bound by position and stepped once per row.
class Statement {
 public:
  Statement(sqlite3* db, const char* sql, const std::string& path) : db_(db), path_(path) {
    if (sqlite3_prepare_v2(db, sql, -1, &s_, nullptr) != SQLITE_OK)
      throw InputError(path_, "", std::string("cannot prepare a statement: ") + sqlite3_errmsg(db));
  }
  ~Statement() { sqlite3_finalize(s_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& text(int i, const std::string& v) {
    check(sqlite3_bind_text(s_, i, v.c_str(), int(v.size()), SQLITE_TRANSIENT));
    return *this;
  }
  // NULL for "".
  Statement& text_or_null(int i, const std::string& v) {
    if (v.empty()) {
      check(sqlite3_bind_null(s_, i));
      return *this;
    }
    return text(i, v);
  }
  Statement& integer(int i, std::int64_t v) {
    check(sqlite3_bind_int64(s_, i, v));
    return *this;
  }
  Statement& real(int i, double v) {
    check(sqlite3_bind_double(s_, i, v));
    return *this;
  }
  // Steps once; true when a row came back.
  bool step() {
    const int rc = sqlite3_step(s_);
    if (rc == SQLITE_ROW) return true;
    if (rc != SQLITE_DONE)
      throw InputError(path_, "", std::string("SQLite failed: ") + sqlite3_errmsg(db_));
    return false;
  }
  void reset() {
    sqlite3_reset(s_);
    sqlite3_clear_bindings(s_);
  }
  std::string column_text(int i) const {
    const unsigned char* t = sqlite3_column_text(s_, i);
    return t ? reinterpret_cast<const char*>(t) : "";
  }
  std::int64_t column_integer(int i) const { return sqlite3_column_int64(s_, i); }
  double column_real(int i) const { return sqlite3_column_double(s_, i); }

 private:
  void check(int rc) const {
    if (rc != SQLITE_OK)
      throw InputError(path_, "", std::string("cannot bind: ") + sqlite3_errmsg(db_));
  }
  sqlite3* db_;
  const std::string& path_;
  sqlite3_stmt* s_ = nullptr;
};

}  // namespace

HistoryDb::HistoryDb(const std::string& path) : path_(path), db_(std::make_unique<Connection>()) {
  db_->path = path;
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) fs::create_directories(parent, ec);
  if (sqlite3_open_v2(path.c_str(), &db_->db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE,
                      nullptr) != SQLITE_OK)
    db_->fail("cannot open the history");
  sqlite3_busy_timeout(db_->db, 10000);  // two CI jobs adding at once wait for each other
  // A file that is not SQLite fails on its first read, here.
  std::int64_t version = 0;
  std::int64_t tables = 0;
  try {
    version = db_->scalar("PRAGMA user_version");
    tables = db_->scalar("SELECT count(*) FROM sqlite_master WHERE type = 'table'");
  } catch (const InputError&) {
    throw InputError(path, "", "is not a shadowbench history (not an SQLite file)");
  }
  db_->exec("PRAGMA foreign_keys = ON");
  if (tables == 0 && version == 0) {
    // Made under the write lock, looked at again there: two CI jobs that
    // open a new file at once make its tables once.
    db_->exec("BEGIN IMMEDIATE");
    if (db_->scalar("SELECT count(*) FROM sqlite_master WHERE type = 'table'") == 0) {
      db_->exec(kCreateTables);
      db_->exec(("PRAGMA user_version = " + std::to_string(kHistorySchemaVersion)).c_str());
    }
    db_->exec("COMMIT");
    version = db_->scalar("PRAGMA user_version");
  }
  if (version != kHistorySchemaVersion)
    throw InputError(path, "PRAGMA user_version",
                     "is " + std::to_string(version) +
                         "; this build reads and writes history version " +
                         std::to_string(kHistorySchemaVersion) +
                         " only (an SQLite file of other tables, or a history of another "
                         "shadowbench: give another --db)");
}

HistoryDb::~HistoryDb() = default;

std::int64_t HistoryDb::run_count() const { return db_->scalar("SELECT count(*) FROM runs"); }

std::vector<HistoryRun> HistoryDb::runs() const {
  Statement q(db_->db,
              "SELECT run_key, run_id, commit_sha, coalesce(started_at, ''), run_dir, "
              "coalesce(host_fingerprint, ''), run_order FROM runs ORDER BY run_order",
              path_);
  std::vector<HistoryRun> out;
  while (q.step()) {
    HistoryRun r;
    r.run_key = q.column_text(0);
    r.run_id = q.column_text(1);
    r.commit = q.column_text(2);
    r.started_at = q.column_text(3);
    r.run_dir = q.column_text(4);
    r.host_fingerprint = q.column_text(5);
    r.run_order = q.column_integer(6);
    out.push_back(std::move(r));
  }
  return out;
}

std::vector<QuantitySeries> HistoryDb::series(const std::string& quantity) const {
  const std::vector<HistoryRun> all = runs();
  std::map<std::string, std::size_t> position;  // run_key -> index in run order
  for (std::size_t i = 0; i < all.size(); ++i) position[all[i].run_key] = i;
  Statement q(db_->db,
              "SELECT j.series, p.run_key, p.value FROM points p "
              "JOIN jobs j USING (run_key, job_id) WHERE p.quantity = ?1 ORDER BY j.series",
              path_);
  q.text(1, quantity);
  std::vector<QuantitySeries> out;
  while (q.step()) {
    const std::string name = q.column_text(0);
    if (out.empty() || out.back().series != name)
      out.push_back({name, std::vector<double>(all.size(), std::nan(""))});
    out.back().values[position.at(q.column_text(1))] = q.column_real(2);
  }
  return out;
}

std::vector<SeriesJobs> HistoryDb::series_jobs() const {
  const std::vector<HistoryRun> all = runs();
  std::map<std::string, std::size_t> position;  // run_key -> index in run order
  for (std::size_t i = 0; i < all.size(); ++i) position[all[i].run_key] = i;
  Statement q(db_->db,
              "SELECT series, scene_variant, resolution, technique_variant, run_key, job_id, "
              "status, coalesce(reason, ''), coalesce(host_fingerprint, '') FROM jobs "
              "ORDER BY series",
              path_);
  std::vector<SeriesJobs> out;
  while (q.step()) {
    const std::string name = q.column_text(0);
    if (out.empty() || out.back().series != name)
      out.push_back({name, q.column_text(1), q.column_text(2), q.column_text(3),
                     std::vector<SeriesJob>(all.size())});
    SeriesJob& job = out.back().runs[position.at(q.column_text(4))];
    job = {true, q.column_text(5), q.column_text(6), q.column_text(7), q.column_text(8)};
  }
  return out;
}

AddedRun HistoryDb::add_run(const std::string& run_dir, const std::string& commit) {
  if (commit.empty()) throw InputError(run_dir, "--commit", "no commit to store the run at");
  // Refuses another schema_version, naming the file, line and pointer.
  const std::vector<JobRecord> records = results::read_job_records(run_dir);
  if (records.empty())
    throw InputError((fs::path(run_dir) / "results.jsonl").string(), "",
                     "holds no job record: nothing to add to the history");

  AddedRun added;
  std::set<std::string> ids;
  for (const JobRecord& r : records) ids.insert(r.run_id);
  for (const std::string& id : ids) added.run_id += (added.run_id.empty() ? "" : "+") + id;
  added.commit = commit;
  std::string started;
  for (const JobRecord& r : records)
    if (r.started_at && (started.empty() || *r.started_at < started)) started = *r.started_at;
  added.run_key = started.empty() ? added.run_id : added.run_id + " " + started;
  const std::vector<JobPoints> jobs = run_points(records);

  db_->exec("BEGIN IMMEDIATE");
  try {
    Statement existing(db_->db, "SELECT commit_sha, run_order FROM runs WHERE run_key = ?1", path_);
    existing.text(1, added.run_key);
    if (existing.step()) {
      const std::string was = existing.column_text(0);
      if (was != commit)
        throw InputError(path_, "run " + added.run_key,
                         "is in the history already, at commit " + was + " (not " + commit +
                             "): a run belongs to one commit");
      added.replaced = true;
      added.run_order = existing.column_integer(1);
      Statement drop(db_->db, "DELETE FROM runs WHERE run_key = ?1", path_);
      drop.text(1, added.run_key).step();
    } else {
      added.run_order = db_->scalar("SELECT coalesce(max(run_order), 0) + 1 FROM runs");
    }

    const JobRecord& first = records.front();
    Statement run(db_->db,
                  "INSERT INTO runs VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12)",
                  path_);
    run.text(1, added.run_key)
        .text(2, added.run_id)
        .integer(3, added.run_order)
        .text(4, commit)
        .text(5, utc_now())
        .text_or_null(6, started)
        .text(7, first.experiment)
        .text(8, first.config_hash)
        .text(9, fs::absolute(run_dir).lexically_normal().string())
        .text_or_null(
            10, common_value(records,
                             [](const JobRecord& r) { return r.host.fingerprint.value_or(""); }))
        .text_or_null(
            11, common_value(records,
                             [](const JobRecord& r) { return r.build.fingerprint.value_or(""); }))
        .integer(12, first.schema_version)
        .step();

    Statement job(db_->db, "INSERT INTO jobs VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10)",
                  path_);
    Statement point(db_->db, "INSERT INTO points VALUES (?1, ?2, ?3, ?4)", path_);
    for (const JobPoints& j : jobs) {
      job.text(1, added.run_key)
          .text(2, j.job_id)
          .text(3, j.series)
          .text(4, j.scene_variant)
          .text(5, j.resolution)
          .text(6, j.technique_variant)
          .text(7, j.status)
          .text_or_null(8, j.reason)
          .text_or_null(9, j.host_fingerprint)
          .text_or_null(10, j.build_fingerprint)
          .step();
      job.reset();
      for (const auto& [quantity, value] : j.values) {
        point.text(1, added.run_key).text(2, j.job_id).text(3, quantity).real(4, value).step();
        point.reset();
        ++added.points;
      }
      ++added.jobs;
    }
    db_->exec("COMMIT");
  } catch (...) {
    sqlite3_exec(db_->db, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
  return added;
}

}  // namespace sb::history
