// `shadowbench history add RUN_DIR [--commit SHA] [--db FILE]`: a run's
// records stored in the history of runs across commits (history/history_db.h);
// `shadowbench history report [--db FILE] [--out DIR]`: its static site
// (history/history_report.h).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli/command_line.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "history/history_db.h"
#include "history/history_report.h"
#include "record/figures.h"
#include "results/compare.h"

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

// --db's default, for add and report.
const char* const kDefaultHistoryDb = "results/history.sqlite";

struct HistoryAddArgs {
  std::string run_dir;
  std::string commit;  // the run's commit
  std::string history_db = kDefaultHistoryDb;
};

struct HistoryReportArgs {
  std::string history_db = kDefaultHistoryDb;
  std::string out;
  std::string history_time = record::time_series().front().option;  // the time plotted
  std::string metric = results::CompareOptions{}.metric;
};

int cmd_history_add(const HistoryAddArgs& a) {
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

int cmd_history_report(const HistoryReportArgs& a) {
  if (!std::filesystem::is_regular_file(a.history_db))
    throw InputError(a.history_db, "--db",
                     "no such history file: `shadowbench history add RUN_DIR --db FILE` makes it");
  HistoryReportOptions options;
  for (const record::TimeSeries& s : record::time_series())
    if (a.history_time == s.option) options.quantities.time = s.key;
  options.quantities.error = "metrics." + a.metric;
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

}  // namespace

void add_history_commands(CommandLine& cl) {
  CLI::App* history = cl.add_command(
      cl.app(), "history",
      "Keep runs across commits in one SQLite file (add), and report every job's time and "
      "error across them with the commits where they stepped (report).",
      "shadowbench history add results/ci-20261206-120000");
  history->require_subcommand(1);

  const auto added = std::make_shared<HistoryAddArgs>();
  CLI::App* add = cl.add_command(
      *history, "add",
      "Store RUN_DIR's records at a commit: every job's times (absolute, and as a ratio to the "
      "control job) and errors, with the host and build fingerprints. Adding a run again at "
      "the same commit replaces it.",
      "shadowbench history add results/ci-20261206-120000 --commit $(git rev-parse HEAD)",
      [added] { return cmd_history_add(*added); });
  add_argument(add, "RUN_DIR", added->run_dir, "a folder `run` or `merge` wrote")->required();
  add->add_option("--commit", added->commit,
                  "the commit the run was built from (default: `git rev-parse HEAD` in the "
                  "current folder)")
      ->type_name("SHA");
  add->add_option("--db", added->history_db, "the history file, created when absent")
      ->type_name("FILE")
      ->capture_default_str();

  const auto reported = std::make_shared<HistoryReportArgs>();
  CLI::App* report = cl.add_command(
      *history, "report",
      "Write a static, offline site of the history into --out: every series' latest time and "
      "error with a sparkline, the steps found in them (change points, with the commit), and "
      "a page per series with its charts and the runs on either side of each step; the steps "
      "also as steps.json.",
      "shadowbench history report --db results/history.sqlite --out results/history",
      [reported] { return cmd_history_report(*reported); });
  report->add_option("--db", reported->history_db, "the history file")
      ->type_name("FILE")
      ->capture_default_str();
  report->add_option("--out", reported->out, "the site's folder (default: results/history)")
      ->type_name("DIR");
  std::vector<std::string> times;
  for (const record::TimeSeries& s : record::time_series()) times.push_back(s.option);
  add_choice(report, "--time", reported->history_time, times,
             "the time plotted: the frame's time over the control's next to it (comparable "
             "across hosts), or this host's milliseconds of the frame or the technique");
  add_metric(report, reported->metric, "the error plotted: a path into a record's metrics");
}

}  // namespace sb::cli
