// The results store (store/results_store.h): after every record it stores,
// results.jsonl holds every record once, in plan order, each line the
// record's own JSON; a record stored again replaces its line, and a store
// reopened on the folder writes the same lines. Opening a store removes
// the temporary files of killed writers (core/atomic_file.h), and only those.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../record/sample_records.h"
#include "core/atomic_file.h"
#include "store/results_store.h"

namespace sb {

using core::AtomicFile;
using record::JobRecord;
using record::JobStatus;
using store::json_text;
using store::ResultsStore;

namespace {

namespace fs = std::filesystem;

fs::path fresh_run_dir() {
  fs::path dir = fs::temp_directory_path() /
                 ("shadowbench_store_" +
                  std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::remove_all(dir);
  return dir;
}

std::vector<std::string> jsonl_lines(const fs::path& dir) {
  std::ifstream in(dir / "results.jsonl");
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::string line_of(const JobRecord& r) { return json_text(r.to_json()); }

JobRecord job(const std::string& technique, JobStatus status = JobStatus::Ok) {
  return test::identity_record("sphere_grid", "64x48", technique, status);
}

TEST(ResultsStore, AfterEveryPutResultsJsonlHoldsEveryRecordOnceInPlanOrder) {
  const fs::path dir = fresh_run_dir();
  ResultsStore store(dir.string());
  const JobRecord a = job("a"), b = job("b"), c = job("c");
  store.set_order({a.job_id, b.job_id, c.job_id});
  store.put(c);
  EXPECT_EQ(jsonl_lines(dir), std::vector<std::string>({line_of(c)}));
  store.put(a);
  EXPECT_EQ(jsonl_lines(dir), std::vector<std::string>({line_of(a), line_of(c)}));
  store.put(b);
  EXPECT_EQ(jsonl_lines(dir), std::vector<std::string>({line_of(a), line_of(b), line_of(c)}));
}

TEST(ResultsStore, ARecordStoredAgainReplacesItsLine) {
  const fs::path dir = fresh_run_dir();
  ResultsStore store(dir.string());
  JobRecord a = job("a", JobStatus::Failed);
  a.reason = "first try";
  const JobRecord b = job("b");
  store.set_order({a.job_id, b.job_id});
  store.put_all({a, b});
  JobRecord again = job("a");
  again.warnings.push_back("second try");
  store.put(again);
  EXPECT_EQ(jsonl_lines(dir), std::vector<std::string>({line_of(again), line_of(b)}));
  ASSERT_NE(store.finished(again.job_id), nullptr);
  EXPECT_EQ(store.finished(again.job_id)->warnings, again.warnings);
}

TEST(ResultsStore, OpeningRemovesWhatKilledWritersLeftAndNothingElse) {
  const fs::path dir = fresh_run_dir();
  fs::create_directories(dir / "records");
  std::vector<fs::path> leftovers{dir / "results.jsonl.tmp-4242"};  // as earlier versions named
  for (const fs::path& final_path : {dir / "results.jsonl", dir / "records" / "a.json"}) {
    const AtomicFile killed(final_path.string());  // its name, as a writer would have used it
    leftovers.push_back(killed.temp_path());
  }
  for (const fs::path& f : leftovers) std::ofstream(f) << "{";
  const fs::path not_temporary = dir / "records" / "notes.tmp-draft";
  std::ofstream(not_temporary) << "kept";
  const ResultsStore store(dir.string());
  for (const fs::path& f : leftovers) EXPECT_FALSE(fs::exists(f)) << f;
  EXPECT_TRUE(fs::exists(not_temporary));
  EXPECT_TRUE(store.untrusted().empty());
}

TEST(ResultsStore, AReopenedStoreWritesTheSameLinesWithEarlierRecordsAfterThePlan) {
  const fs::path dir = fresh_run_dir();
  const JobRecord a = job("a"), b = job("b"), earlier = job("earlier");
  {
    ResultsStore store(dir.string());
    store.put_all({earlier, b, a});
  }
  fs::remove(dir / "results.jsonl");
  ResultsStore reopened(dir.string());
  reopened.set_order({a.job_id, b.job_id});
  reopened.rewrite_index();
  EXPECT_EQ(jsonl_lines(dir), std::vector<std::string>({line_of(a), line_of(b), line_of(earlier)}));
}

}  // namespace
}  // namespace sb
