// `shadowbench history add RUN_DIR [--commit SHA] [--db FILE]`: a run's
// records stored in the history of runs across commits (history/history_db.h);
// `shadowbench history report [--db FILE] [--out DIR]`: its static site
// (history/history_report.h).
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli/commands.h"
#include "core/error.h"
#include "history/history_db.h"
#include "history/history_report.h"

namespace sb::cli {

using core::InputError;
using core::kExitOk;
using history::AddedRun;
using history::HistoryDb;
using history::HistoryReport;
using history::HistoryReportOptions;
using history::ReportedStep;

namespace {

// `git rev-parse HEAD` in the current folder, or "" outside a repository.
std::string head_commit() {
  FILE* p = popen("git rev-parse --verify --quiet HEAD 2>/dev/null", "r");
  if (!p) return "";
  char buf[128] = {};
  std::string out;
  while (std::fgets(buf, sizeof buf, p)) out += buf;
  if (pclose(p) != 0) return "";
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

}  // namespace

int cmd_history_add(const Args& a) {
  std::string commit = a.commit;
  if (commit.empty()) commit = head_commit();
  if (commit.empty())
    throw InputError(a.run_dir, "--commit",
                     "no commit given, and the current folder is not in a git repository: "
                     "give --commit SHA");
  history::check_commit(a.run_dir, commit);  // before the file is made
  HistoryDb db(a.history_db);
  const AddedRun r = db.add_run(a.run_dir, commit);
  std::printf("%s run %s at commit %s: %zu jobs, %zu values; run %lld of %lld in %s\n",
              r.replaced ? "replaced" : "added", r.run_key.c_str(), r.commit.c_str(), r.jobs,
              r.points, static_cast<long long>(r.run_order), static_cast<long long>(db.run_count()),
              db.path().c_str());
  return kExitOk;
}

int cmd_history_report(const Args& a) {
  if (!std::filesystem::is_regular_file(a.history_db))
    throw InputError(a.history_db, "--db",
                     "no such history file: `shadowbench history add RUN_DIR --db FILE` makes it");
  HistoryReportOptions options;
  options.quantities.time =
      a.history_time == "ratio" ? "time.frame_ratio" : "time." + a.history_time;
  options.quantities.error = "metrics." + a.compare.metric;
  const HistoryDb db(a.history_db);
  const std::string out = a.out.empty() ? "results/history" : a.out;
  const HistoryReport r = history::write_history_report(db, out, options);
  std::printf("history: %zu runs, %zu series, %zu host(s), %zu step(s)\n", r.runs, r.series,
              r.hosts, r.steps.size());
  for (const ReportedStep& s : r.steps)
    std::printf("  step at run %lld (commit %s): %s, %s %.4g -> %.4g (%+.1f %%)\n",
                static_cast<long long>(s.run_order), s.commit.c_str(), s.series.c_str(),
                s.quantity.c_str(), s.change.before, s.change.after,
                100.0 * s.change.relative_change);
  std::printf("report: %s\n", r.index.c_str());
  return kExitOk;
}

}  // namespace sb::cli
