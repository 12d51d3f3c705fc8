// `shadowbench history add RUN_DIR [--commit SHA] [--db FILE]`: a run's
// records stored in the history of runs across commits (history/history_db.h).
#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "core/error.h"
#include "history/history_db.h"

namespace sb::cli {

using core::InputError;
using core::kExitOk;
using history::AddedRun;
using history::HistoryDb;

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
  HistoryDb db(a.history_db);
  const AddedRun r = db.add_run(a.run_dir, commit);
  std::printf("%s run %s at commit %s: %zu jobs, %zu values; run %lld of %lld in %s\n",
              r.replaced ? "replaced" : "added", r.run_key.c_str(), r.commit.c_str(), r.jobs,
              r.points, static_cast<long long>(r.run_order), static_cast<long long>(db.run_count()),
              db.path().c_str());
  return kExitOk;
}

}  // namespace sb::cli
