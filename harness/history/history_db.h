#pragma once
// The history of many runs across commits: one SQLite file
// (Debian's libsqlite3, no server) that `shadowbench history add` fills
// run by run and `history report` reads. Its tables, described in
// docs/ci.md ("History across commits"):
//   runs    one row per run: its key (run_key: its records' run_id and
//           the time its first job started, so that a CI job writing to
//           the same --out folder at every commit adds a new run each
//           time), its id, its place in the history (run_order:
//           the order runs were added, which CI makes commit order), the
//           commit, dates, experiment, config hash, run folder, and the
//           host and build fingerprints of its records (when all agree)
//   jobs    one row per (run, job): its series, status and fingerprints
//   points  one row per (run, job, quantity) with its value and, for a
//           time, the job's own noise of it (run_points.h; NULL: unknown)
// The file records its layout's version (PRAGMA user_version); a file of
// another version, or one that is not a history, is refused naming it;
// version 1 (no points.noise) is read, and upgraded by a writer.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sb::history {

// The layout of the tables above; a change to them changes it.
inline constexpr int kHistorySchemaVersion = 2;

struct AddedRun {
  std::string run_id;
  std::string run_key;  // run_id and its first job's started_at: "ci 2026-12-06T10:00:00Z"
  std::string commit;
  std::int64_t run_order = 0;  // 1 for the history's first run
  std::size_t jobs = 0, points = 0;
  bool replaced = false;  // the run was there already (same commit): its rows were replaced
};

// One run of the history, as `runs` holds it.
struct HistoryRun {
  std::string run_key, run_id, commit, started_at, run_dir, host_fingerprint;
  std::int64_t run_order = 0;
};

// One series' values of a quantity, one per run of the history in run
// order: NaN where that run has no value (the job was not in it, skipped,
// failed, or did not reach the number), so that position i is runs()[i]
// for every series, as the change-point detector takes them.
struct QuantitySeries {
  std::string series;  // "scene @ resolution / technique"
  std::vector<double> values;
  std::vector<double> noise;  // each run's own noise of its value (run_points.h), NaN: unknown
};

// One job of a series in one run of the history.
struct SeriesJob {
  bool present = false;  // the run had this series' job
  std::string job_id, status, reason, host_fingerprint;
};

// A series and its job in each run, in run order (runs() by position).
struct SeriesJobs {
  std::string series;  // "scene @ resolution / technique"
  std::string scene_variant, resolution, technique_variant;
  std::vector<SeriesJob> runs;
};

// Refuses (InputError naming --commit) a commit a history does not store:
// empty, longer than kMaxCommitCharacters, not UTF-8, or holding a control
// character (stored_text.h).
void check_commit(const std::string& run_dir, const std::string& commit);

class HistoryDb {
 public:
  // Opens the history at `path`, creating it (and its folder) when absent.
  // InputError naming the file when it is not a history of this version.
  explicit HistoryDb(const std::string& path);
  ~HistoryDb();
  HistoryDb(const HistoryDb&) = delete;
  HistoryDb& operator=(const HistoryDb&) = delete;

  // Stores the records of the run folder `run_dir` (its results.jsonl, a
  // merged run's included) at `commit`, in one transaction. Adding a run
  // (the same run_key) again at the same commit replaces its rows and keeps its place (so it
  // is idempotent, and a resumed run's later add completes it); at another
  // commit it is an InputError, as are records of another schema version
  // (named by file, line and pointer) and a folder without records.
  // The run's id is its records' run_id; the shards of a merged run each
  // keep their own, and the run's id is theirs sorted and joined by "+".
  AddedRun add_run(const std::string& run_dir, const std::string& commit);

  std::int64_t run_count() const;
  std::vector<HistoryRun> runs() const;  // in run order
  // Every series with at least one value of `quantity` ("time.frame_ratio",
  // "metrics.visibility.all.rmse", ...), by series name.
  std::vector<QuantitySeries> series(const std::string& quantity) const;
  // Every series of the history, by name, with its job in each run.
  std::vector<SeriesJobs> series_jobs() const;
  const std::string& path() const { return path_; }

 private:
  struct Connection;
  std::string path_;
  std::unique_ptr<Connection> db_;
  bool has_noise_ = true;  // points.noise exists (not in a read-only version-1 file)
};

}  // namespace sb::history
