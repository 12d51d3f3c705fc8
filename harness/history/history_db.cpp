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
#include "history/stored_text.h"
#include "record/job_record.h"
#include "store/results_store.h"

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
  noise REAL,
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
    return t ? std::string(reinterpret_cast<const char*>(t),
                           static_cast<std::size_t>(sqlite3_column_bytes(s_, i)))
             : "";
  }
  // The column's text, refused (naming the table, row and column) when it
  // is not what a history stores (stored_text.h).
  std::string checked_text(int i, const std::string& place) const {
    std::string t = column_text(i);
    if (const std::string problem = text_problem(t); !problem.empty())
      throw InputError(path_, place, problem);
    return t;
  }
  int column_type(int i) const { return sqlite3_column_type(s_, i); }
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

// "runs row 2 (run_order)": a place in the history for a message.
std::string row_place(const char* table, std::int64_t rowid, const char* column) {
  return std::string(table) + " row " + std::to_string(rowid) + " (" + column + ")";
}

// Refuses a run_order that is not an integer from 1 to kMaxRunOrder.
void check_run_order(const std::string& path, std::int64_t rowid, int type, std::int64_t order) {
  if (type != SQLITE_INTEGER)
    throw InputError(path, row_place("runs", rowid, "run_order"),
                     "run_order is not an integer (the file was made or edited by hand)");
  if (order < 1 || order > kMaxRunOrder)
    throw InputError(path, row_place("runs", rowid, "run_order"),
                     "run_order " + std::to_string(order) + " is outside 1 to " +
                         std::to_string(kMaxRunOrder) +
                         ", the orders a history holds (the file was made or edited by hand)");
}

}  // namespace

void check_commit(const std::string& run_dir, const std::string& commit) {
  if (const std::string problem = commit_problem(commit); !problem.empty())
    throw InputError(run_dir, "--commit", quoted_excerpt(commit) + " " + problem);
}

HistoryDb::HistoryDb(const std::string& path) : path_(path), db_(std::make_unique<Connection>()) {
  db_->path = path;
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) fs::create_directories(parent, ec);
  if (sqlite3_open_v2(path.c_str(), &db_->db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE,
                      nullptr) != SQLITE_OK)
    db_->fail("cannot open the history");
  sqlite3_busy_timeout(db_->db, 10000);   // two CI jobs adding at once wait for each other
  db_->exec("PRAGMA foreign_keys = ON");  // (a no-op inside a transaction)
  // The version and the tables are read, and a new file's tables made, in
  // one write transaction (a read one when the file is read-only): a writer
  // that opens a new file while another makes its tables sees both before
  // or both after (read apart, one saw user_version 0 and the
  // tables, and refused the file). A file that is not SQLite fails here.
  const bool read_only = sqlite3_db_readonly(db_->db, "main") == 1;
  std::int64_t version = 0;
  std::int64_t tables = 0;
  try {
    db_->exec(read_only ? "BEGIN" : "BEGIN IMMEDIATE");
    version = db_->scalar("PRAGMA user_version");
    tables = db_->scalar("SELECT count(*) FROM sqlite_master WHERE type = 'table'");
  } catch (const InputError&) {
    const int code = sqlite3_errcode(db_->db);
    if (code == SQLITE_BUSY || code == SQLITE_LOCKED) throw;  // not the file's fault
    throw InputError(path, "", "is not a shadowbench history (not an SQLite file)");
  }
  try {
    if (tables == 0 && version == 0 && !read_only) {
      db_->exec(kCreateTables);
      db_->exec(("PRAGMA user_version = " + std::to_string(kHistorySchemaVersion)).c_str());
      version = kHistorySchemaVersion;
    }
    // Version 1 had no points.noise: a writer adds the column (NULL: the
    // runs before it have no own noise); a reader reads NULL for it.
    if (version == 1 && !read_only) {
      db_->exec("ALTER TABLE points ADD COLUMN noise REAL");
      db_->exec(("PRAGMA user_version = " + std::to_string(kHistorySchemaVersion)).c_str());
      version = kHistorySchemaVersion;
    }
    if (version == 1) has_noise_ = false;
    db_->exec("COMMIT");
  } catch (...) {
    sqlite3_exec(db_->db, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
  if (version != kHistorySchemaVersion && version != 1)
    throw InputError(
        path, "PRAGMA user_version",
        "is " + std::to_string(version) + "; this build reads and writes history version " +
            std::to_string(kHistorySchemaVersion) +
            " (and reads version 1) only (an SQLite file of other tables, or a history of another "
            "shadowbench: give another --db)");
}

HistoryDb::~HistoryDb() = default;

std::int64_t HistoryDb::run_count() const { return db_->scalar("SELECT count(*) FROM runs"); }

std::vector<HistoryRun> HistoryDb::runs() const {
  Statement q(db_->db,
              "SELECT run_key, run_id, commit_sha, coalesce(started_at, ''), run_dir, "
              "coalesce(host_fingerprint, ''), run_order, rowid FROM runs ORDER BY run_order",
              path_);
  std::vector<HistoryRun> out;
  while (q.step()) {
    const std::int64_t row = q.column_integer(7);
    HistoryRun r;
    r.run_key = q.checked_text(0, row_place("runs", row, "run_key"));
    r.run_id = q.checked_text(1, row_place("runs", row, "run_id"));
    r.commit = q.checked_text(2, row_place("runs", row, "commit_sha"));
    if (const std::string problem = commit_problem(r.commit); !problem.empty())
      throw InputError(path_, row_place("runs", row, "commit_sha"),
                       quoted_excerpt(r.commit) + " " + problem);
    r.started_at = q.checked_text(3, row_place("runs", row, "started_at"));
    r.run_dir = q.checked_text(4, row_place("runs", row, "run_dir"));
    r.host_fingerprint = q.checked_text(5, row_place("runs", row, "host_fingerprint"));
    r.run_order = q.column_integer(6);
    check_run_order(path_, row, q.column_type(6), r.run_order);
    out.push_back(std::move(r));
  }
  return out;
}

std::vector<QuantitySeries> HistoryDb::series(const std::string& quantity) const {
  const std::vector<HistoryRun> all = runs();
  std::map<std::string, std::size_t> position;  // run_key -> index in run order
  for (std::size_t i = 0; i < all.size(); ++i) position[all[i].run_key] = i;
  Statement q(db_->db,
              has_noise_ ? "SELECT j.series, p.run_key, p.value, p.rowid, j.rowid, p.job_id, "
                           "p.noise FROM points p LEFT JOIN jobs j USING (run_key, job_id) "
                           "WHERE p.quantity = ?1 ORDER BY j.series"
                         : "SELECT j.series, p.run_key, p.value, p.rowid, j.rowid, p.job_id, "
                           "NULL FROM points p LEFT JOIN jobs j USING (run_key, job_id) "
                           "WHERE p.quantity = ?1 ORDER BY j.series",
              path_);
  q.text(1, quantity);
  std::vector<QuantitySeries> out;
  while (q.step()) {
    const std::int64_t row = q.column_integer(3);
    const std::string run_key = q.checked_text(1, row_place("points", row, "run_key"));
    if (q.column_type(4) == SQLITE_NULL)
      throw InputError(path_, row_place("points", row, "job_id"),
                       "names job " + quoted_excerpt(q.column_text(5)) + " of run " +
                           quoted_excerpt(run_key) +
                           ", which has no row of jobs (the file was made or edited by hand)");
    const std::string name = q.checked_text(0, row_place("jobs", q.column_integer(4), "series"));
    const auto at = position.find(run_key);
    if (at == position.end())
      throw InputError(path_, row_place("points", row, "run_key"),
                       "names run " + quoted_excerpt(run_key) +
                           ", which runs does not hold (the file was made or edited by hand)");
    const int type = q.column_type(2);
    const double value = q.column_real(2);
    if ((type != SQLITE_FLOAT && type != SQLITE_INTEGER) || !std::isfinite(value))
      throw InputError(path_, row_place("points", row, "value"),
                       type == SQLITE_FLOAT || type == SQLITE_INTEGER
                           ? "is " + std::string(std::isnan(value) ? "NaN" : "infinite") +
                                 "; a history holds finite numbers only"
                           : "is not a number; a history holds finite numbers only");
    if (out.empty() || out.back().series != name)
      out.push_back({name, std::vector<double>(all.size(), std::nan("")),
                     std::vector<double>(all.size(), std::nan(""))});
    out.back().values[at->second] = value;
    // A noise that is not a finite number >= 0 is no noise (the file was
    // edited): the run is weighed as a typical one.
    if (q.column_type(6) == SQLITE_FLOAT || q.column_type(6) == SQLITE_INTEGER) {
      const double noise = q.column_real(6);
      if (std::isfinite(noise) && noise >= 0) out.back().noise[at->second] = noise;
    }
  }
  return out;
}

std::vector<SeriesJobs> HistoryDb::series_jobs() const {
  const std::vector<HistoryRun> all = runs();
  std::map<std::string, std::size_t> position;  // run_key -> index in run order
  for (std::size_t i = 0; i < all.size(); ++i) position[all[i].run_key] = i;
  Statement q(db_->db,
              "SELECT series, scene_variant, resolution, technique_variant, run_key, job_id, "
              "status, coalesce(reason, ''), coalesce(host_fingerprint, ''), rowid FROM jobs "
              "ORDER BY series",
              path_);
  static constexpr const char* kColumns[] = {
      "series", "scene_variant", "resolution", "technique_variant", "run_key",
      "job_id", "status",        "reason",     "host_fingerprint"};
  std::vector<SeriesJobs> out;
  while (q.step()) {
    const std::int64_t row = q.column_integer(9);
    std::string text[9];
    for (int i = 0; i < 9; ++i) text[i] = q.checked_text(i, row_place("jobs", row, kColumns[i]));
    const auto at = position.find(text[4]);
    if (at == position.end())
      throw InputError(path_, row_place("jobs", row, "run_key"),
                       "names run " + quoted_excerpt(text[4]) +
                           ", which runs does not hold (the file was made or edited by hand)");
    if (out.empty() || out.back().series != text[0])
      out.push_back({text[0], text[1], text[2], text[3], std::vector<SeriesJob>(all.size())});
    out.back().runs[at->second] = {true, text[5], text[6], text[7], text[8]};
  }
  return out;
}

AddedRun HistoryDb::add_run(const std::string& run_dir, const std::string& commit) {
  if (commit.empty()) throw InputError(run_dir, "--commit", "no commit to store the run at");
  check_commit(run_dir, commit);
  // Refuses another schema_version, naming the file, line and pointer.
  const std::vector<JobRecord> records = store::read_job_records(run_dir);
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
  std::vector<JobPoints> jobs = run_points(records);
  // What is stored is what a history reads back (stored_text.h): a reason
  // is cut to the bound, anything else too long is refused.
  const std::string records_file = (fs::path(run_dir) / "results.jsonl").string();
  auto check = [&](const std::string& text, const std::string& what) {
    if (const std::string problem = text_problem(text); !problem.empty())
      throw InputError(records_file, what, quoted_excerpt(text) + " " + problem);
  };
  check(added.run_key, "run_id and started_at");
  for (JobPoints& j : jobs) {
    if (j.reason.size() > kMaxStoredTextBytes)
      j.reason = utf8_cut(j.reason, kMaxStoredTextBytes - 3) + "\u2026";
    for (const std::string* t :
         {&j.job_id, &j.series, &j.scene_variant, &j.resolution, &j.technique_variant, &j.status,
          &j.reason, &j.host_fingerprint, &j.build_fingerprint})
      check(*t, "job " + quoted_excerpt(j.job_id));
  }

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
      // Every order is checked (a hand-made file may hold any), and the
      // next is the largest plus one, when there is room for it.
      Statement orders(db_->db,
                       "SELECT rowid, typeof(run_order) = 'integer', run_order FROM runs "
                       "ORDER BY typeof(run_order) = 'integer', run_order NOT BETWEEN 1 AND ?1 "
                       "DESC, run_order DESC LIMIT 1",
                       path_);
      orders.integer(1, kMaxRunOrder);
      added.run_order = 1;
      if (orders.step()) {
        const std::int64_t row = orders.column_integer(0);
        const std::int64_t last = orders.column_integer(2);
        check_run_order(path_, row, orders.column_integer(1) != 0 ? SQLITE_INTEGER : SQLITE_TEXT,
                        last);
        if (last == kMaxRunOrder)
          throw InputError(path_, row_place("runs", row, "run_order"),
                           "run_order " + std::to_string(last) +
                               " is the largest a history holds: no run can follow it (start "
                               "another history, or renumber its runs from 1)");
        added.run_order = last + 1;
      }
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
    Statement point(db_->db,
                    "INSERT INTO points (run_key, job_id, quantity, value, noise) "
                    "VALUES (?1, ?2, ?3, ?4, ?5)",
                    path_);
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
        point.text(1, added.run_key).text(2, j.job_id).text(3, quantity).real(4, value);
        if (const auto noise = j.noise.find(quantity); noise != j.noise.end())
          point.real(5, noise->second);
        point.step();
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
