// A run killed with SIGKILL, parent and children, mid-batch: the rerun in
// the same folder finishes it with every record there exactly once, none
// torn, and results.jsonl equal to the record files. A record file that
// cannot be trusted is reported and its job rerun.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <fstream>
#include <map>
#include <set>
#include <thread>

#include "isolation_util.h"

namespace sb::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// Six slow jobs (0.1 s a frame, four frames each, plus the set-up).
json slow_experiment() {
  return small_experiment(json::array(
      {{{"name", "fault"}, {"params", {{"slow_ms", {100, 101, 102, 103, 104, 105}}}}}, "none"}));
}

size_t record_files(const fs::path& run_dir) {
  size_t n = 0;
  if (!fs::exists(run_dir / "records")) return 0;
  for (const auto& e : fs::directory_iterator(run_dir / "records"))
    n += e.path().extension() == ".json" ? 1 : 0;
  return n;
}

// The run folder must be as if the run had never been interrupted: one
// record per job in records/ and in results.jsonl, the same ones, no
// temporary files.
void expect_consistent(const fs::path& run_dir, size_t jobs) {
  std::map<std::string, json> files;
  for (const auto& e : fs::directory_iterator(run_dir / "records")) {
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
    std::ifstream in(e.path());
    const json j = json::parse(in, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << e.path();
    files[j["job_id"]] = j;
  }
  for (const auto& e : fs::directory_iterator(run_dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
  const auto lines = jsonl_records(run_dir);
  EXPECT_EQ(lines.size(), jobs);
  EXPECT_EQ(files.size(), jobs);
  std::set<std::string> seen;
  for (const auto& line : lines) {
    EXPECT_TRUE(seen.insert(line["job_id"]).second) << "twice: " << line["job_id"];
    EXPECT_EQ(line["status"], "ok") << line.dump(1);
    ASSERT_TRUE(files.count(line["job_id"])) << line["job_id"];
    EXPECT_EQ(line, files[line["job_id"]]) << line["job_id"];
  }
}

TEST(ResumeAfterKill, ARunKilledWithSigkillMidBatchResumesWithEveryRecordOnce) {
  const auto dir = test_folder();
  const auto config = write_config(dir, slow_experiment());
  const fs::path out = dir / "run";
  // The killed run's processes become ours when their parent dies, so that
  // the rerun below starts only once every one of them has gone: kill()
  // returns before a process has exited and closed its files, and the rerun
  // would otherwise race the driver's exit for the folder's lock.
  ASSERT_EQ(::prctl(PR_SET_CHILD_SUBREAPER, 1), 0);
  // The run in a process group of its own, so that one kill reaches the
  // driver and its child as a user's Ctrl-\ or a scheduler's kill would.
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::setpgid(0, 0);
    const std::string cmd =
        shadowbench_command("run " + config + " --out " + out.string() + " --no-cache --quiet") +
        " > /dev/null 2>&1";
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::setpgid(pid, pid);
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (record_files(out) < 2 && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ::kill(-pid, SIGKILL);
  int status = 0;
  while (::waitpid(-pid, &status, 0) > 0 || errno == EINTR) {
  }
  EXPECT_EQ(errno, ECHILD);
  ::prctl(PR_SET_CHILD_SUBREAPER, 0);
  const size_t before_kill = record_files(out);
  ASSERT_GE(before_kill, 2u);
  ASSERT_LT(before_kill, 7u) << "the run finished before it could be killed";

  // The rerun takes the folder: the killed run left no lock behind.
  const CliRun rerun = run_shadowbench("run " + config + " --out " + out.string() + " --no-cache");
  EXPECT_EQ(rerun.exit_code, 0) << rerun.output;
  EXPECT_NE(rerun.output.find("0 failed, " + std::to_string(before_kill) + " resumed"),
            std::string::npos)
      << "killed after " << before_kill << " records\n"
      << rerun.output;
  expect_consistent(out, 7);
}

TEST(ResumeAfterKill, AnUntrustedRecordFileIsReportedAndItsJobRerun) {
  const auto dir = test_folder();
  const auto config =
      write_config(dir, small_experiment(json::array({"none", "shadow_map", "pcf_box"})));
  const fs::path out = dir / "run";
  const std::string run = "run " + config + " --out " + out.string() + " --no-cache --no-images";
  ASSERT_EQ(run_shadowbench(run).exit_code, 0);

  // One record torn in half, one replaced by another job's.
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(out / "records")) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  ASSERT_EQ(files.size(), 3u);
  std::string text;
  {
    std::ifstream in(files[0]);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  std::ofstream(files[0], std::ios::trunc) << text.substr(0, text.size() / 2);
  fs::copy_file(files[2], files[1], fs::copy_options::overwrite_existing);
  // What a writer killed before its rename leaves.
  std::ofstream(out / "records" / (files[2].filename().string() + ".tmp-4242")) << "{";

  const CliRun rerun = run_shadowbench(run);
  EXPECT_EQ(rerun.exit_code, 0) << rerun.output;
  EXPECT_NE(rerun.output.find("shadowbench: warning: " + files[0].string()), std::string::npos)
      << rerun.output;
  EXPECT_NE(rerun.output.find(files[1].string() + ": holds the record of job"), std::string::npos)
      << rerun.output;
  EXPECT_NE(rerun.output.find("its job runs again"), std::string::npos);
  EXPECT_NE(rerun.output.find("2 ok, 0 skipped, 0 failed, 1 resumed"), std::string::npos)
      << rerun.output;
  EXPECT_NE(rerun.output.find("2 earlier record files could not be trusted"), std::string::npos)
      << rerun.output;
  expect_consistent(out, 3);
}

}  // namespace
}  // namespace sb::test
