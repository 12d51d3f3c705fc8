// Every case of the hostile corpus (make_hostile.py: malformed, oversized,
// degenerate and crafted configs and glTF files, special paths) goes through
// `shadowbench validate` and `shadowbench run` as a child process under
// limits. None may crash (die by a signal), hang (60 s wall clock), exit 3
// (internal error) or use more than 1 GiB of memory (peak resident set). Exit
// 2 must come with an error message.
//
// The address-space limit (RLIMIT_AS) is a second guard that stops a runaway
// allocation at once; it is 2 GiB, not 1, because Embree and TBB reserve
// about 1 GiB of address space when the reference's device is created
// (measured: `run` fails with "out of memory" under `ulimit -v 1048576`).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

namespace fs = std::filesystem;

constexpr long kMaxResidentKib = 1L << 20;         // 1 GiB
constexpr rlim_t kAddressSpace = rlim_t(2) << 30;  // see above
constexpr int kWallSeconds = 60;

struct Case {
  std::string name;
  std::string config;  // bytes: some paths are not UTF-8 on purpose
  std::string out;
  std::vector<int> validate, run;
  double seconds = kWallSeconds;  // each command's bound
};

// gtest prints a parameter that fails: its name is enough.
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

std::string from_hex(const std::string& hex) {
  std::string out;
  for (size_t i = 0; i + 1 < hex.size(); i += 2)
    out += char(std::stoi(hex.substr(i, 2), nullptr, 16));
  return out;
}

std::vector<Case> load_cases() {
  std::ifstream in(SHADOWBENCH_HOSTILE_DIR "/manifest.json");
  if (!in) return {};  // HostileCorpus.HasCases fails then
  const nlohmann::json doc = nlohmann::json::parse(in);
  std::vector<Case> cases;
  for (const auto& c : doc) {
    Case k;
    k.name = c["name"];
    k.config = from_hex(c["config"]);
    k.out = c["out"].is_null() ? std::string(SHADOWBENCH_HOSTILE_DIR "/runs/") + k.name
                               : from_hex(c["out"]);
    k.validate = c["validate"].get<std::vector<int>>();
    k.run = c["run"].get<std::vector<int>>();
    if (c.contains("seconds") && !c["seconds"].is_null()) k.seconds = c["seconds"].get<double>();
    cases.push_back(std::move(k));
  }
  return cases;
}

const std::vector<Case>& cases() {
  static const std::vector<Case> c = load_cases();
  return c;
}

struct Outcome {
  bool finished = false;  // false: killed after kWallSeconds
  int exit_code = -1;     // -1 when it died by a signal
  int signal = 0;
  long max_rss_kib = 0;
  double seconds = 0;
  std::string output;
};

Outcome run_limited(const std::vector<std::string>& args, const std::string& log) {
  Outcome o;
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      ::dup2(fd, 1);
      ::dup2(fd, 2);
    }
    const rlimit as{kAddressSpace, kAddressSpace};
    ::setrlimit(RLIMIT_AS, &as);
    std::vector<char*> argv;
    argv.reserve(args.size() + 1);
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  rusage usage{};
  // Woken by the child's exit (a pidfd turns readable), not by polling: a
  // 20 ms poll cost about 10 ms a command, 2 s over the corpus.
  const int pidfd = static_cast<int>(::syscall(SYS_pidfd_open, pid, 0));
  while (pidfd >= 0) {
    const auto left = std::chrono::seconds(kWallSeconds) - (std::chrono::steady_clock::now() - t0);
    pollfd exited{pidfd, POLLIN, 0};
    const int ready =
        ::poll(&exited, 1,
               int(std::max<std::int64_t>(
                   0, std::chrono::duration_cast<std::chrono::milliseconds>(left).count())));
    if (ready < 0 && errno == EINTR) continue;
    o.finished = ready > 0;
    break;
  }
  while (pidfd < 0) {  // a kernel without pidfd_open (before Linux 5.3)
    if (::wait4(pid, &status, WNOHANG, &usage) == pid) {
      o.finished = true;
      break;
    }
    if (std::chrono::steady_clock::now() - t0 > std::chrono::seconds(kWallSeconds)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (pidfd >= 0) ::close(pidfd);
  if (!o.finished) ::kill(pid, SIGKILL);
  if (pidfd >= 0 || !o.finished) ::wait4(pid, &status, 0, &usage);
  o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  o.max_rss_kib = usage.ru_maxrss;
  if (WIFEXITED(status)) o.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) o.signal = WTERMSIG(status);
  std::ifstream in(log, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  o.output = ss.str();
  return o;
}

void check(const Case& c, const std::string& command, const std::vector<std::string>& args,
           const std::vector<int>& allowed) {
  SCOPED_TRACE(command);
  const std::string log = std::string(SHADOWBENCH_HOSTILE_DIR "/logs/") + c.name + "." + command;
  const Outcome o = run_limited(args, log);
  ASSERT_TRUE(o.finished) << "still running after " << kWallSeconds << " s";
  ASSERT_EQ(o.signal, 0) << "died by signal " << o.signal << ":\n" << o.output;
  EXPECT_NE(o.exit_code, 3) << o.output;
  EXPECT_NE(std::find(allowed.begin(), allowed.end(), o.exit_code), allowed.end())
      << "exit " << o.exit_code << ":\n"
      << o.output;
  EXPECT_LE(o.max_rss_kib, kMaxResidentKib) << "peak resident set " << o.max_rss_kib << " KiB";
  EXPECT_LE(o.seconds, c.seconds) << "took " << o.seconds << " s";
  if (o.exit_code == 2) {
    EXPECT_NE(o.output.find("shadowbench: error: "), std::string::npos) << o.output;
  }
  std::printf("%s %s: exit %d in %.2f s, peak %ld MiB\n", c.name.c_str(), command.c_str(),
              o.exit_code, o.seconds, o.max_rss_kib >> 10);
}

class HostileInput : public ::testing::TestWithParam<Case> {};

TEST_P(HostileInput, ValidateAndRunFailCleanly) {
  const Case& c = GetParam();
  fs::create_directories(SHADOWBENCH_HOSTILE_DIR "/logs");
  std::error_code ec;
  fs::remove_all(c.out, ec);  // each run starts afresh
  check(c, "validate", {SHADOWBENCH_EXE, "validate", c.config}, c.validate);
  check(c, "run",
        {SHADOWBENCH_EXE, "run", c.config, "--out", c.out, "--quiet", "--no-cache", "--no-images"},
        c.run);
}

INSTANTIATE_TEST_SUITE_P(Corpus, HostileInput, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& p) { return p.param.name; });

TEST(HostileCorpus, HasCases) { EXPECT_GE(cases().size(), 100u) << SHADOWBENCH_HOSTILE_DIR; }

}  // namespace
