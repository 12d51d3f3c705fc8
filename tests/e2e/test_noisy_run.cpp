// A job timed beside busy processes is flagged as noisy, out loud: its
// record's timing.noise, its console line, the run's last line, summary.md
// and the HTML report. The load is made on purpose and made large: more
// busy processes than the run may use cores, each switching between
// spinning and sleeping at random a few milliseconds at a time, so that some
// of the job's frames share the CPU and others do not; with 10 timed frames
// the median's interval, [x_(2), x_(9)], then spans both.
#include <gtest/gtest.h>
#include <sched.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "../common/cli_run.h"
#include "../common/text.h"
#include "../config/cli_runner.h"
#include "e2e_util.h"

namespace sb::test {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Busy processes for as long as it lives, killed (by their ids) and reaped
// when it ends.
class BusyLoops {
 public:
  explicit BusyLoops(int count) {
    for (int i = 0; i < count; ++i) {
      const pid_t pid = ::fork();
      if (pid == 0) spin_and_sleep(unsigned(i));  // never returns
      if (pid > 0) pids_.push_back(pid);
    }
  }
  ~BusyLoops() {
    for (pid_t pid : pids_) ::kill(pid, SIGKILL);
    for (pid_t pid : pids_) ::waitpid(pid, nullptr, 0);
  }
  BusyLoops(const BusyLoops&) = delete;
  BusyLoops& operator=(const BusyLoops&) = delete;

 private:
  // Spins 1-12 ms, sleeps 0-6 ms, at random, until killed.
  [[noreturn]] static void spin_and_sleep(unsigned seed) {
    std::mt19937 rng(seed * 7919u + 1u);
    std::uniform_int_distribution<int> spin_us(1000, 12000), sleep_us(0, 6000);
    volatile std::uint64_t sink = 0;
    for (;;) {
      const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(spin_us(rng));
      while (std::chrono::steady_clock::now() < until) sink = sink + 1;
      std::this_thread::sleep_for(std::chrono::microseconds(sleep_us(rng)));
    }
  }
  std::vector<pid_t> pids_;
};

int usable_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  return ::sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : 2;
}

// The line of `text` that holds `needle`, or "".
std::string line_with(const std::string& text, const std::string& needle) {
  const size_t at = text.find(needle);
  if (at == std::string::npos) return "";
  const size_t from = text.rfind('\n', at) + 1;
  return text.substr(from, text.find('\n', at) - from);
}

TEST(NoisyRun, AJobTimedBesideBusyProcessesIsFlaggedInTheRecordTheConsoleAndTheReport) {
  const fs::path dir = fresh_test_folder("noisy_run_");
  // One job (and the control, "none", timed next to it); a threshold of
  // ±2 %: what the load makes is several times that (docs/ci.md, "Noisy jobs").
  const json config = {
      {"name", "noisy"},
      {"scenes", {small_scene(2.0)}},
      {"techniques", {{{"name", "pcf_box"}, {"params", {{"k", 3}, {"size", 512}}}}}},
      {"resolutions", {{160, 120}}},
      {"frames", {{"warmup", 2}, {"timed", 10}, {"noise_threshold", 0.02}}},
      {"reference", {{"spp", 4}}}};
  std::ofstream(dir / "noisy.json") << config.dump(2);
  const fs::path run_dir = dir / "run";
  CliResult run;
  {
    BusyLoops load(2 * usable_cores() + 1);
    run = run_cli("run " + (dir / "noisy.json").string() + " --out " + run_dir.string() +
                  " --no-images --cache-dir " + (dir / "cache").string());
  }
  ASSERT_EQ(run.exit_code, 0) << run.output;

  const auto records = jsonl_records(run_dir);
  ASSERT_EQ(records.size(), 1u);
  const json& noise = records[0]["timing"]["noise"];
  ASSERT_TRUE(noise.is_object()) << records[0]["timing"].dump();
  EXPECT_TRUE(noise["noisy"].get<bool>()) << noise.dump();
  EXPECT_EQ(noise["threshold"], 0.02);
  const double widest =
      std::max(noise["frame_ci_rel"].get<double>(), noise.value("frame_ratio_ci_rel", 0.0));
  EXPECT_GT(widest, 0.02) << noise.dump();
  EXPECT_EQ(noise["usable_cores"], usable_cores());
  EXPECT_TRUE(noise.contains("load_average_start") && noise.contains("load_average_end"));
  EXPECT_EQ(records[0]["timing"]["frame"]["median_ci_rel"], noise["frame_ci_rel"]);

  // The console: the job's line, then the run's last line.
  const std::string job = line_with(run.output, "pcf_box/k=3,size=512: ok");
  EXPECT_NE(job.find("  noisy ±"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("shadowbench: warning: 1 of 1 timed jobs were noisy (the median's 95 % "
                            "interval wider than ±2 %); the load average was "),
            std::string::npos)
      << run.output;

  // The tables: summary.md's row and legend, and the HTML report's.
  const std::string md = read_text(run_dir / "summary.md");
  EXPECT_NE(line_with(md, "| pcf_box/k=3,size=512 |").find("†"), std::string::npos) << md;
  EXPECT_NE(md.find("† noisy: the median's 95 % interval"), std::string::npos) << md;
  const auto report = run_cli("report " + run_dir.string() + " --no-viewer-data");
  ASSERT_EQ(report.exit_code, 0) << report.output;
  const std::string html = read_text(run_dir / "report" / "index.html");
  EXPECT_NE(html.find("<p class=\"note noisy\">† noisy:"), std::string::npos);
}

}  // namespace

}  // namespace sb::test
