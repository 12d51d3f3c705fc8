// The history's SQLite store (history/history_db.h), checked against the
// run's own results.jsonl read as plain JSON, and the file read back
// through SQLite's C API: not through the store's own reader.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "../common/cli_run.h"
#include "core/error.h"
#include "history/change_points.h"
#include "history/history_db.h"
#include "history_fixture.h"

namespace sb::test {
namespace {

namespace fs = std::filesystem;
using history::AddedRun;
using history::HistoryDb;
using nlohmann::json;

// One value of the history file, by SQL, read with SQLite itself.
std::optional<double> query_number(const fs::path& db_file, const std::string& sql) {
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open_v2(db_file.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* s = nullptr;
  EXPECT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr), SQLITE_OK) << sqlite3_errmsg(db);
  std::optional<double> v;
  if (sqlite3_step(s) == SQLITE_ROW && sqlite3_column_type(s, 0) != SQLITE_NULL)
    v = sqlite3_column_double(s, 0);
  sqlite3_finalize(s);
  sqlite3_close(db);
  return v;
}

std::string query_text(const fs::path& db_file, const std::string& sql) {
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open_v2(db_file.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* s = nullptr;
  EXPECT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr), SQLITE_OK) << sqlite3_errmsg(db);
  std::string v;
  if (sqlite3_step(s) == SQLITE_ROW && sqlite3_column_text(s, 0))
    v = reinterpret_cast<const char*>(sqlite3_column_text(s, 0));
  sqlite3_finalize(s);
  sqlite3_close(db);
  return v;
}

std::string point_sql(const std::string& job, const std::string& quantity) {
  return "SELECT value FROM points WHERE job_id = '" + job + "' AND quantity = '" + quantity + "'";
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const core::InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

TEST(HistoryDb, AddStoresEveryJobsTimesAndErrorsAsItsRecordsHoldThem) {
  const fs::path dir = test_folder("sb_history_");
  const fs::path file = dir / "h.sqlite";
  const fs::path run = run_folder(dir, "run");
  const std::vector<json> records = jsonl_records(run);
  ASSERT_GE(records.size(), 2u);

  const AddedRun added = HistoryDb(file.string()).add_run(run.string(), "c0ffee");
  EXPECT_EQ(added.run_id, records[0]["run_id"].get<std::string>());
  EXPECT_EQ(added.run_order, 1);
  EXPECT_FALSE(added.replaced);
  EXPECT_EQ(added.jobs, records.size());

  EXPECT_EQ(query_text(file, "SELECT commit_sha FROM runs"), "c0ffee");
  // The key: the run id and the first start of its jobs (ISO 8601 sorts as text).
  std::string first_start = records[0]["started_at"];
  for (const json& j : records)
    first_start = std::min(first_start, j["started_at"].get<std::string>());
  EXPECT_EQ(added.run_key, added.run_id + " " + first_start);
  EXPECT_EQ(query_text(file, "SELECT run_key FROM runs"), added.run_key);
  EXPECT_EQ(query_text(file, "SELECT host_fingerprint FROM runs"),
            records[0]["host"]["fingerprint"].get<std::string>());
  EXPECT_EQ(query_text(file, "SELECT build_fingerprint FROM runs"),
            records[0]["build"]["fingerprint"].get<std::string>());
  EXPECT_EQ(query_number(file, "SELECT count(*) FROM jobs"), double(records.size()));
  EXPECT_EQ(query_number(file, "PRAGMA user_version"), double(history::kHistorySchemaVersion));

  int timed = 0;
  for (const json& j : records) {
    const std::string id = j["job_id"];
    EXPECT_EQ(query_text(file, "SELECT status FROM jobs WHERE job_id = '" + id + "'"),
              j["status"].get<std::string>());
    const json::json_pointer ratio("/timing/control/frame_ratio/median");
    if (j.contains(ratio)) {
      ++timed;
      EXPECT_DOUBLE_EQ(*query_number(file, point_sql(id, "time.frame_ratio")),
                       j[ratio].get<double>())
          << id;
    }
    const json::json_pointer frame("/timing/frame/median_ms");
    if (j.contains(frame)) {
      EXPECT_DOUBLE_EQ(*query_number(file, point_sql(id, "time.frame_ms")), j[frame].get<double>());
    }
    const json::json_pointer technique("/timing/technique/median_ms");
    if (j.contains(technique)) {
      EXPECT_DOUBLE_EQ(*query_number(file, point_sql(id, "time.technique_ms")),
                       j[technique].get<double>());
    }
    const json::json_pointer rmse("/metrics/visibility/all/rmse");
    if (j.contains(rmse)) {
      EXPECT_DOUBLE_EQ(*query_number(file, point_sql(id, "metrics.visibility.all.rmse")),
                       j[rmse].get<double>());
    }
    // Every number under "metrics" is a point: count them in the JSON.
    int numbers = 0;
    std::function<void(const json&)> count = [&](const json& v) {
      if (v.is_object())
        for (const auto& item : v.items()) count(item.value());
      else if (v.is_number())
        ++numbers;
    };
    if (j.contains("metrics")) count(j["metrics"]);
    EXPECT_EQ(query_number(file, "SELECT count(*) FROM points WHERE job_id = '" + id +
                                     "' AND quantity LIKE 'metrics.%'"),
              double(numbers))
        << id;
  }
  EXPECT_GE(timed, 2) << "the baseline's jobs should be timed against the control";
}

TEST(HistoryDb, RunsTakeTheOrderTheyWereAddedInAndAddingOneAgainReplacesItInItsPlace) {
  const fs::path dir = test_folder("sb_history_");
  const std::string file = (dir / "h.sqlite").string();
  const auto renamed = [](const std::string& id) { return [id](json& j) { j["run_id"] = id; }; };
  const fs::path a = run_folder(dir, "a", renamed("a"));
  const fs::path b = run_folder(dir, "b", renamed("b"));
  {
    HistoryDb db(file);
    EXPECT_EQ(db.add_run(a.string(), "1111").run_order, 1);
    EXPECT_EQ(db.add_run(b.string(), "2222").run_order, 2);
  }
  const double points = *query_number(dir / "h.sqlite", "SELECT count(*) FROM points");
  HistoryDb db(file);  // reopened: the file is the history
  const AddedRun again = db.add_run(a.string(), "1111");
  EXPECT_TRUE(again.replaced);
  EXPECT_EQ(again.run_order, 1);
  EXPECT_EQ(db.run_count(), 2);
  EXPECT_EQ(query_number(dir / "h.sqlite", "SELECT count(*) FROM points"), points);
  EXPECT_EQ(query_text(dir / "h.sqlite", "SELECT run_id FROM runs ORDER BY run_order DESC"), "b");
}

TEST(HistoryDb, ARunAtAnotherCommitIsRefusedNamingBothAndTheHistoryKeepsIt) {
  const fs::path dir = test_folder("sb_history_");
  const std::string file = (dir / "h.sqlite").string();
  const fs::path run = run_folder(dir, "run");
  HistoryDb db(file);
  db.add_run(run.string(), "aaaa");
  const std::string m = message_of([&] { db.add_run(run.string(), "bbbb"); });
  EXPECT_NE(m.find(file), std::string::npos) << m;
  EXPECT_NE(m.find("at commit aaaa (not bbbb)"), std::string::npos) << m;
  EXPECT_NE(m.find("run ci "), std::string::npos) << m;
  EXPECT_EQ(query_text(dir / "h.sqlite", "SELECT commit_sha FROM runs"), "aaaa");
}

TEST(HistoryDb, TheSameOutFolderRunAgainAtTheNextCommitIsANewRun) {
  const fs::path dir = test_folder("sb_history_");
  HistoryDb db((dir / "h.sqlite").string());
  db.add_run(run_folder(dir, "first").string(), "aaaa");
  // The same run id ("ci", from --out results/ci), started a day later.
  const fs::path next = run_folder(dir, "next", [](json& j) {
    std::string t = j["started_at"];
    t[9] = char(t[9] == '9' ? '0' : t[9] + 1);  // yyyy-mm-dD: another day
    j["started_at"] = t;
  });
  const AddedRun added = db.add_run(next.string(), "bbbb");
  EXPECT_FALSE(added.replaced);
  EXPECT_EQ(added.run_order, 2);
  EXPECT_EQ(db.run_count(), 2);
}

TEST(HistoryDb, RecordsOfAnotherSchemaVersionAreRefusedByFileLineAndPointerAndAddNothing) {
  const fs::path dir = test_folder("sb_history_");
  const std::string file = (dir / "h.sqlite").string();
  const fs::path run = run_folder(dir, "run", [](json& j) { j["schema_version"] = 2; });
  HistoryDb db(file);
  const std::string m = message_of([&] { db.add_run(run.string(), "aaaa"); });
  EXPECT_NE(m.find((run / "results.jsonl").string()), std::string::npos) << m;
  EXPECT_NE(m.find("line 1"), std::string::npos) << m;
  EXPECT_NE(m.find("/schema_version"), std::string::npos) << m;
  EXPECT_EQ(db.run_count(), 0);
}

TEST(HistoryDb, AFileThatIsNotAHistoryOfThisVersionIsRefusedNamingIt) {
  const fs::path dir = test_folder("sb_history_");
  const fs::path junk = dir / "junk.sqlite";
  std::ofstream(junk) << "not a database, but long enough to be read as one's header....\n";
  EXPECT_NE(message_of([&] {
              HistoryDb d(junk.string());
            }).find(junk.string() + ": is not a shadowbench history"),
            std::string::npos);

  for (const std::string& setup : {std::string("CREATE TABLE other(x); PRAGMA user_version = 0;"),
                                   std::string("CREATE TABLE runs(x); PRAGMA user_version = 7;")}) {
    const fs::path other = dir / "other.sqlite";
    fs::remove(other);
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(other.c_str(), &db), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(db, setup.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(db);
    const std::string m = message_of([&] { HistoryDb d(other.string()); });
    EXPECT_NE(m.find(other.string()), std::string::npos) << m;
    EXPECT_NE(
        m.find("this build reads and writes history version " +
               std::to_string(history::kHistorySchemaVersion) + " (and reads version 1) only"),
        std::string::npos)
        << m;
  }
}

// A job's own noise as the history defines it, computed here from the
// definition: the sign test's 95 % interval of the median,
// [x_(j), x_(n+1-j)] with j the largest rank whose tail P(B <= j - 1),
// B ~ Binomial(n, 1/2), is at most 2.5 %; its half-width over the median,
// / 1.96.
double own_noise_of(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  const size_t n = x.size();
  size_t j = 0;
  double tail = 0, term = std::pow(0.5, double(n));  // P(B = 0)
  for (size_t k = 0; k < n; ++k) {
    tail += term;  // P(B <= k)
    if (tail > 0.025) break;
    j = k + 1;                              // the rank k + 1 keeps the tail
    term *= double(n - k) / double(k + 1);  // P(B = k + 1)
  }
  const double median = n % 2 ? x[n / 2] : (x[n / 2 - 1] + x[n / 2]) / 2;
  return (x[n - j] - x[j - 1]) / 2 / median / 1.959963984540054;
}

TEST(HistoryDb, EachTimeIsStoredWithTheJobsOwnNoiseFromItsFrames) {
  const fs::path dir = test_folder("sb_history_");
  const fs::path file = dir / "h.sqlite";
  const fs::path run = run_folder(dir, "run");
  HistoryDb(file.string()).add_run(run.string(), "c0ffee");
  int checked = 0;
  for (const json& j : jsonl_records(run)) {
    const json::json_pointer samples("/timing/control/frame_ratio/samples");
    if (!j.contains(samples)) continue;
    const std::string id = j["job_id"];
    const std::optional<double> noise =
        query_number(file, "SELECT noise FROM points WHERE job_id = '" + id +
                               "' AND quantity = 'time.frame_ratio'");
    ASSERT_TRUE(noise) << id;
    EXPECT_NEAR(*noise, own_noise_of(j[samples].get<std::vector<double>>()), 1e-12) << id;
    ++checked;
  }
  EXPECT_GE(checked, 2);
  // Errors have no own noise: they do not vary from run to run.
  EXPECT_EQ(query_number(file, "SELECT count(noise) FROM points WHERE quantity LIKE 'metrics.%'"),
            0.0);
}

TEST(HistoryDb, AVersionOneHistoryIsUpgradedAndItsRunsHaveNoOwnNoise) {
  const fs::path dir = test_folder("sb_history_");
  const fs::path file = dir / "h.sqlite";
  HistoryDb(file.string())
      .add_run(run_folder(dir, "old", [](json& j) { start_on_day(j, 1); }).string(), "aaaa");
  // What version 1 was: points without the noise column.
  sqlite3* raw = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &raw), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(raw, "ALTER TABLE points DROP COLUMN noise; PRAGMA user_version = 1;",
                         nullptr, nullptr, nullptr),
            SQLITE_OK)
      << sqlite3_errmsg(raw);
  sqlite3_close(raw);

  HistoryDb db(file.string());
  EXPECT_EQ(query_number(file, "PRAGMA user_version"), double(history::kHistorySchemaVersion));
  db.add_run(run_folder(dir, "new", [](json& j) { start_on_day(j, 2); }).string(), "bbbb");
  const std::vector<history::QuantitySeries> series = db.series("time.frame_ratio");
  ASSERT_FALSE(series.empty());
  for (const history::QuantitySeries& s : series) {
    ASSERT_EQ(s.noise.size(), 2u);
    EXPECT_TRUE(std::isnan(s.noise[0])) << s.series;  // the old run's
    EXPECT_GT(s.noise[1], 0.0) << s.series;           // the new run's
  }
}

TEST(HistoryDb, AMergedRunsShardsMakeOneRunNamedByTheirIds) {
  const fs::path dir = test_folder("sb_history_");
  int line = 0;
  const fs::path run =
      run_folder(dir, "merged", [&](json& j) { j["run_id"] = (line++ % 2) ? "ci-2" : "ci-1"; });
  HistoryDb db((dir / "h.sqlite").string());
  EXPECT_EQ(db.add_run(run.string(), "aaaa").run_id, "ci-1+ci-2");
  EXPECT_EQ(db.run_count(), 1);
}

TEST(HistoryDb, AFolderWithoutRecordsIsRefused) {
  const fs::path dir = test_folder("sb_history_");
  fs::create_directories(dir / "empty");
  std::ofstream(dir / "empty" / "results.jsonl") << "";
  HistoryDb db((dir / "h.sqlite").string());
  const std::string m = message_of([&] { db.add_run((dir / "empty").string(), "aaaa"); });
  EXPECT_NE(m.find("holds no job record"), std::string::npos) << m;
}

// The case at the store's level: ten runs of the ci baseline, 2 %
// lognormal noise on every job's time ratio, and one job 30 % slower from
// the sixth run on. The detector, fed the store's series, flags that job at
// that run and nothing else.
TEST(HistoryDb, TenRunsWithOneJobThirtyPercentSlowerFromTheSixthGiveThatStepAndNoOther) {
  const fs::path dir = test_folder("sb_history_");
  HistoryDb db((dir / "h.sqlite").string());
  const json::json_pointer ratio("/timing/control/frame_ratio/median");
  const std::string slowed = jsonl_records(kCiBaseline).at(2)["job_id"];
  std::mt19937_64 rng(44);
  std::normal_distribution<double> z(0.0, 1.0);
  std::map<std::string, std::vector<double>> written;  // job_id -> ratios by run
  for (int run = 0; run < 10; ++run) {
    const fs::path folder = run_folder(dir, "run" + std::to_string(run), [&](json& j) {
      start_on_day(j, run + 1);
      if (!j.contains(ratio)) return;
      double v = j[ratio].get<double>() * std::exp(0.02 * z(rng));
      if (j["job_id"] == slowed && run >= 5) v *= 1.3;
      j[ratio] = v;
      written[j["job_id"]].push_back(v);
    });
    db.add_run(folder.string(), "commit" + std::to_string(run));
  }
  ASSERT_EQ(db.run_count(), 10);
  ASSERT_EQ(written.count(slowed), 1u);
  const std::vector<history::QuantitySeries> series = db.series("time.frame_ratio");
  ASSERT_EQ(series.size(), written.size());
  int steps = 0;
  for (const history::QuantitySeries& s : series) {
    ASSERT_EQ(s.values.size(), 10u);
    const std::vector<history::ChangePoint> found = history::find_change_points(s.values);
    steps += int(found.size());
    if (s.series.find(jsonl_records(kCiBaseline).at(2)["technique_variant"].get<std::string>()) !=
        std::string::npos) {
      ASSERT_EQ(found.size(), 1u) << s.series;
      EXPECT_EQ(found[0].index, 5u);
      EXPECT_NEAR(found[0].relative_change, 0.3, 0.05);
    }
  }
  EXPECT_EQ(steps, 1);
  // The store's values are the records', run by run.
  for (const history::QuantitySeries& s : series) {
    bool matched = false;
    for (const auto& [job, values] : written) {
      if (values == s.values) matched = true;
    }
    EXPECT_TRUE(matched) << s.series;
  }
}

TEST(HistoryDb, ARunWithoutAJobLeavesThatSeriesANaNAtItsPlace) {
  const fs::path dir = test_folder("sb_history_");
  HistoryDb db((dir / "h.sqlite").string());
  const std::string dropped = jsonl_records(kCiBaseline).at(0)["job_id"];
  db.add_run(run_folder(dir, "a", [](json& j) { j["run_id"] = "a"; }).string(), "1");
  const fs::path b = dir / "b";
  fs::create_directories(b);
  {
    std::ofstream out(b / "results.jsonl");
    for (json j : jsonl_records(kCiBaseline)) {
      j["run_id"] = "b";
      if (j["job_id"] != dropped) out << j.dump() << "\n";
    }
  }
  db.add_run(b.string(), "2");
  const std::vector<history::HistoryRun> runs = db.runs();
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].run_id, "a");
  EXPECT_EQ(runs[1].commit, "2");
  int with_gap = 0;
  for (const history::QuantitySeries& s : db.series("time.frame_ms")) {
    ASSERT_EQ(s.values.size(), 2u);
    EXPECT_FALSE(std::isnan(s.values[0])) << s.series;
    if (std::isnan(s.values[1])) ++with_gap;
  }
  EXPECT_EQ(with_gap, 1);
}

TEST(HistoryCli, AddPrintsWhatItStoredAndABadHistoryExitsWithCode2) {
  const fs::path dir = test_folder("sb_history_cli_");
  const std::string exe = SHADOWBENCH_BINARY_DIR "/shadowbench";
  const fs::path run = run_folder(dir, "run");
  const std::string db = (dir / "h.sqlite").string();
  CliRun r = run_command(exe + " history add " + run.string() + " --commit abc --db " + db);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.rfind("added run ci ", 0), 0u) << r.output;
  EXPECT_NE(r.output.find(" at commit abc: "), std::string::npos) << r.output;
  r = run_command(exe + " history add " + run.string() + " --commit def --db " + db);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(db), std::string::npos) << r.output;
}

}  // namespace
}  // namespace sb::test
