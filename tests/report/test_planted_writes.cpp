// A run folder from elsewhere may hold symlinks at the
// names report and merge write (the final names and the temporary names
// next to them), pointing at a file of the user's. Each such write must
// replace the symlink with a regular file of its own and leave the file it
// pointed at unchanged (core/atomic_file). No GL: report and merge read the
// committed CI baseline's records.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "../common/cli_run.h"

namespace sb {
namespace {

namespace fs = std::filesystem;

constexpr const char* kVictim = "# the user's own file, outside every run folder\n";
constexpr int kCounters = 64;
constexpr const char* kMergeMarker =
    ".shadowbench-merge";  // results/merge.cpp  // temporary names planted per target and pid

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Every regular file under `dir`, relative to it.
std::vector<fs::path> files_under(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out.push_back(fs::relative(e.path(), dir));
  return out;
}

// Runs shadowbench with `args` (stdout and stderr into *output). In the
// child, before exec (the pid stays), a symlink to `victim` is planted at
// "<target>.tmp-<pid>" and "<target>.tmp-<pid>-<n>" for every target: the
// names this process's writers would take.
int run_planted(const std::vector<std::string>& args, const std::vector<fs::path>& targets,
                const fs::path& victim, const fs::path& log, std::string* output) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const std::string me = std::to_string(::getpid());
    for (const fs::path& t : targets) {
      const std::string base = t.string() + ".tmp-" + me;
      (void)!::symlink(victim.c_str(), base.c_str());
      for (int n = 0; n < kCounters; ++n)
        (void)!::symlink(victim.c_str(), (base + "-" + std::to_string(n)).c_str());
    }
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    std::vector<char*> argv{const_cast<char*>(SHADOWBENCH_EXE)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(SHADOWBENCH_EXE, argv.data());
    ::_exit(127);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  *output = read_all(log);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A copy of the CI baseline's records as a run folder.
fs::path baseline_run(const fs::path& dir) {
  fs::create_directories(dir);
  fs::copy_file(fs::path(SHADOWBENCH_SOURCE_DIR) / "results/baselines/ci/results.jsonl",
                dir / "results.jsonl");
  return dir;
}

// Plants a symlink to `victim` at every `rel` under `dir` (its folders made).
std::vector<fs::path> plant(const fs::path& dir, const std::vector<fs::path>& rels,
                            const fs::path& victim) {
  std::vector<fs::path> targets;
  for (const fs::path& rel : rels) {
    fs::create_directories((dir / rel).parent_path());
    fs::create_symlink(victim, dir / rel);
    targets.push_back(dir / rel);
  }
  return targets;
}

void expect_replaced(const std::vector<fs::path>& targets, const fs::path& victim,
                     const std::string& output) {
  const std::string now = read_all(victim);
  EXPECT_TRUE(now == kVictim) << "the file outside the folder was written through a symlink, now "
                              << now.size() << " bytes starting " << now.substr(0, 120) << "\n"
                              << output;
  for (const fs::path& t : targets)
    EXPECT_EQ(fs::symlink_status(t).type(), fs::file_type::regular) << t << "\n" << output;
}

TEST(PlantedSymlinks, ReportReplacesThemAndNeverWritesThrough) {
  const fs::path dir = test::test_folder("sb_planted_");
  // What report writes, from a clean run of it.
  const fs::path clean = baseline_run(dir / "clean");
  std::string output;
  ASSERT_EQ(run_planted({"report", clean.string()}, {}, dir / "none", dir / "clean.log", &output),
            0)
      << output;
  std::vector<fs::path> written;
  // Not the viewer's folder: report replaces it only when its marker is a
  // file report wrote, and refuses it otherwise (tested on its own).
  for (const fs::path& rel : files_under(clean))
    if (rel != "results.jsonl" && rel.parent_path() != "report/viewer") written.push_back(rel);
  ASSERT_GE(written.size(), 3u);  // results.csv, summary.md, report/index.html at least

  const fs::path victim = dir / "bashrc";
  std::ofstream(victim, std::ios::binary) << kVictim;
  const fs::path run = baseline_run(dir / "hostile");
  const std::vector<fs::path> targets = plant(run, written, victim);
  ASSERT_EQ(run_planted({"report", run.string()}, targets, victim, dir / "hostile.log", &output), 0)
      << output;
  expect_replaced(targets, victim, output);
  EXPECT_EQ(read_all(run / "results.csv"), read_all(clean / "results.csv"));
}

TEST(PlantedSymlinks, MergeReplacesThemAndNeverWritesThrough) {
  const fs::path dir = test::test_folder("sb_planted_");
  const fs::path shard = baseline_run(dir / "shard");
  std::string output;
  ASSERT_EQ(run_planted({"merge", (dir / "clean").string(), shard.string()}, {}, dir / "none",
                        dir / "clean.log", &output),
            0)
      << output;
  // Not the records: merge refuses a folder whose records/ holds anything.
  // Its marker a regular file, as an earlier merge (or whoever made the
  // folder) leaves it: merge then writes into the folder.
  std::vector<fs::path> written;
  for (const fs::path& rel : files_under(dir / "clean"))
    if (rel != ".lock" && rel != kMergeMarker && rel.parent_path() != "records")
      written.push_back(rel);
  ASSERT_GE(written.size(), 3u);  // results.jsonl, results.csv, summary.md

  const fs::path victim = dir / "bashrc";
  std::ofstream(victim, std::ios::binary) << kVictim;
  const fs::path out = dir / "hostile";
  const std::vector<fs::path> targets = plant(out, written, victim);
  fs::copy_file(dir / "clean" / kMergeMarker, out / kMergeMarker);
  ASSERT_EQ(run_planted({"merge", out.string(), shard.string()}, targets, victim,
                        dir / "hostile.log", &output),
            0)
      << output;
  expect_replaced(targets, victim, output);
  EXPECT_EQ(read_all(out / "results.jsonl"), read_all(dir / "clean" / "results.jsonl"));
}

// The run folder's lock file, written with the holder's pid, is not opened
// through a symlink: merge refuses, naming it, and the file is unchanged.
TEST(PlantedSymlinks, ALockFileThatIsASymlinkIsRefused) {
  const fs::path dir = test::test_folder("sb_planted_");
  const fs::path shard = baseline_run(dir / "shard");
  const fs::path victim = dir / "bashrc";
  std::ofstream(victim, std::ios::binary) << kVictim;
  fs::create_directories(dir / "out");
  std::ofstream(dir / "out" / kMergeMarker) << "";  // a merge's folder, as far as it shows
  fs::create_symlink(victim, dir / "out" / ".lock");
  std::string output;
  EXPECT_NE(run_planted({"merge", (dir / "out").string(), shard.string()}, {}, victim,
                        dir / "merge.log", &output),
            0)
      << output;
  EXPECT_NE(output.find((dir / "out" / ".lock").string()), std::string::npos) << output;
  EXPECT_NE(output.find("symlink"), std::string::npos) << output;
  EXPECT_EQ(read_all(victim), kVictim);
}

// A folder the tool makes for itself, planted as a symlink to a folder
// elsewhere: report refuses, naming it, and writes nothing there.
TEST(PlantedSymlinks, AReportFolderThatIsASymlinkIsRefused) {
  const fs::path dir = test::test_folder("sb_planted_");
  const fs::path run = baseline_run(dir / "run");
  fs::create_directories(dir / "elsewhere");
  fs::create_symlink(dir / "elsewhere", run / "report");
  std::string output;
  EXPECT_NE(run_planted({"report", run.string()}, {}, dir / "none", dir / "report.log", &output), 0)
      << output;
  EXPECT_NE(output.find((run / "report").string() + " is a symlink"), std::string::npos) << output;
  EXPECT_TRUE(fs::is_empty(dir / "elsewhere")) << output;
}

// The folders the tool makes inside a folder it writes: report --latex's
// latex/ in the report, and history report's series/ in its site. Planted as
// symlinks to a folder elsewhere, each is refused, named, and nothing is
// written there.
TEST(PlantedSymlinks, ALatexFolderThatIsASymlinkIsRefused) {
  const fs::path dir = test::test_folder("sb_planted_");
  const fs::path run = baseline_run(dir / "run");
  fs::create_directories(dir / "elsewhere");
  fs::create_directories(run / "report");
  fs::create_symlink(dir / "elsewhere", run / "report" / "latex");
  std::string output;
  EXPECT_NE(run_planted({"report", run.string(), "--latex", "--no-viewer-data"}, {}, dir / "none",
                        dir / "report.log", &output),
            0)
      << output;
  EXPECT_NE(output.find((run / "report" / "latex").string() + " is a symlink"), std::string::npos)
      << output;
  EXPECT_TRUE(fs::is_empty(dir / "elsewhere")) << output;
}

TEST(PlantedSymlinks, AHistorySitesSeriesFolderThatIsASymlinkIsRefused) {
  const fs::path dir = test::test_folder("sb_planted_");
  const fs::path run = baseline_run(dir / "run");
  const fs::path db = dir / "history.sqlite";
  std::string output;
  ASSERT_EQ(
      run_planted({"history", "add", run.string(), "--commit", "abc1234", "--db", db.string()}, {},
                  dir / "none", dir / "add.log", &output),
      0)
      << output;
  fs::create_directories(dir / "elsewhere");
  fs::create_directories(dir / "site");
  fs::create_symlink(dir / "elsewhere", dir / "site" / "series");
  EXPECT_NE(
      run_planted({"history", "report", "--db", db.string(), "--out", (dir / "site").string()}, {},
                  dir / "none", dir / "report.log", &output),
      0)
      << output;
  EXPECT_NE(output.find((dir / "site" / "series").string() + " is a symlink"), std::string::npos)
      << output;
  EXPECT_TRUE(fs::is_empty(dir / "elsewhere")) << output;
}

}  // namespace
}  // namespace sb
