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

#include "../common/text.h"

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

// glTF node and mesh names reached the terminal raw (an
// OSC sequence set the terminal's title, CSI 2J cleared it) and were cut at
// byte 77, inside a character. `scene info` and `run` print them escaped and
// cut between characters.
TEST(HostileMessages, GltfNamesReachTheTerminalEscapedAndWhole) {
  const fs::path dir = fs::temp_directory_path() / "hostile_gltf_names";
  std::error_code ec;
  fs::remove_all(dir, ec);
  fs::create_directories(dir);
  std::string long_name;
  for (int i = 0; i < 100; ++i) long_name += "\u65e5";  // 日, three bytes each
  std::string doc =
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1]}],)"
      R"("nodes":[{"mesh":0,"name":"\u001b]0;pwned\u0007\u001b[2Jfloor"},)"
      R"({"mesh":1,"name":")" +
      long_name +
      R"("}],)"
      R"("meshes":[{"name":"m\u001b[31m","primitives":[{"attributes":{"POSITION":0}}]},)"
      R"({"primitives":[{"attributes":{"POSITION":1}}]}],)"
      R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)"
      R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"},)"
      R"({"byteLength":36,"uri":"data:application/octet-stream;base64,)"
      R"(AAAAAAAAAAAAAIA/AACAPwAAAAAAAIA/AAAAAAAAgD8AAMA/"}],)"
      R"("bufferViews":[{"buffer":0,"byteLength":36},{"buffer":1,"byteLength":36}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
      R"("min":[0,0,0],"max":[1,1,0]},{"bufferView":1,"componentType":5126,"count":3,)"
      R"("type":"VEC3","min":[0,0,1],"max":[1,1,1.5]}]})";
  std::ofstream(dir / "names.gltf") << doc;
  const nlohmann::json config = {
      {"name", "names"},
      {"scenes", {{{"type", "gltf"}, {"params", {{"file", (dir / "names.gltf").string()}}}}}},
      {"techniques", {"none", "shadow_volume"}},
      {"resolutions", {{24, 16}}},
      {"frames", {{"warmup", 0}, {"timed", 1}}},
      {"reference", {{"spp", 4}, {"cache", false}}}};
  std::ofstream(dir / "config.json") << config.dump();
  const std::vector<std::vector<std::string>> commands = {
      {SHADOWBENCH_EXE, "scene", "info", (dir / "names.gltf").string()},
      {SHADOWBENCH_EXE, "validate", (dir / "config.json").string()},
      {SHADOWBENCH_EXE, "run", (dir / "config.json").string(), "--out", (dir / "run").string(),
       "--no-cache", "--no-images"}};
  for (const auto& args : commands) {
    SCOPED_TRACE(args[1]);
    const Outcome o = run_limited(args, (dir / (args[1] + ".log")).string());
    ASSERT_TRUE(o.finished);
    EXPECT_EQ(o.signal, 0);
    EXPECT_EQ(o.output.find('\x1b'), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find('\x07'), std::string::npos) << o.output;
    EXPECT_TRUE(sb::test::valid_utf8(o.output)) << o.output;
    if (args[1] == "scene") {
      EXPECT_EQ(o.exit_code, 0) << o.output;
      EXPECT_NE(o.output.find("\\x1B]0;pwned\\x07\\x1B[2Jfloor"), std::string::npos) << o.output;
    }
  }
}

// tinygltf's error for an undecodable data URI quotes the
// whole URI. A 50 MiB one (made here, not in the corpus: the build tree
// would keep it) once made a 56 MB stderr line, a 56 MB reason in every
// failed job and a run folder of 909 MB at 1.5 GB resident. Messages that
// quote input are cut (core/bounded_text.h: 200 characters a quote, 2000 a
// reason), so the terminal output, each reason and the folder stay small, and
// the peak resident set is what reading the file costs (measured on the
// 2-core development VM: 362 MiB).
TEST(HostileMessages, FiftyMegabyteBadDataUriGivesBoundedMessagesAndFolder) {
  const fs::path dir = fs::temp_directory_path() / "hostile_big_data_uri";
  std::error_code ec;
  fs::remove_all(dir, ec);
  fs::create_directories(dir);
  {
    std::ofstream g(dir / "big.gltf", std::ios::binary);
    g << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
         R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)"
      << std::string(std::size_t(50) << 20, '@')
      << R"("}],"bufferViews":[{"buffer":0,"byteLength":36}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
         R"("min":[0,0,0],"max":[1,1,0]}]})";
  }
  const nlohmann::json config = {
      {"name", "big_data_uri"},
      {"scenes", {{{"type", "gltf"}, {"params", {{"file", (dir / "big.gltf").string()}}}}}},
      {"techniques", {"none"}},
      {"resolutions", {{24, 16}, {32, 16}, {40, 16}}},
      {"frames", {{"warmup", 0}, {"timed", 1}}},
      {"reference", {{"spp", 4}, {"cache", false}}}};
  std::ofstream(dir / "config.json") << config.dump();
  const fs::path out = dir / "run";
  const Outcome o = run_limited({SHADOWBENCH_EXE, "run", (dir / "config.json").string(), "--out",
                                 out.string(), "--no-cache", "--no-images"},
                                (dir / "run.log").string());
  fs::remove(dir / "big.gltf", ec);
  ASSERT_TRUE(o.finished);
  ASSERT_EQ(o.signal, 0) << o.output.substr(0, 4000);
  EXPECT_TRUE(o.exit_code == 1 || o.exit_code == 2) << o.output.substr(0, 4000);
  EXPECT_LT(o.output.size(), 64u << 10) << o.output.substr(0, 4000);
  EXPECT_EQ(o.output.find('\x1b'), std::string::npos);
  constexpr long kMaxKib = 640L << 10;  // 640 MiB: the file and tinygltf's copies of it
  EXPECT_LE(o.max_rss_kib, kMaxKib) << "peak resident set " << o.max_rss_kib << " KiB";
  std::uintmax_t folder = 0;
  for (const auto& e : fs::recursive_directory_iterator(out))
    if (e.is_regular_file()) folder += e.file_size();
  EXPECT_LT(folder, std::uintmax_t(1) << 20) << "the run folder holds " << folder << " bytes";
  std::ifstream jsonl(out / "results.jsonl");
  int failed = 0;
  for (std::string line; std::getline(jsonl, line);) {
    const nlohmann::json r = nlohmann::json::parse(line);
    if (r.value("status", "") != "failed") continue;
    ++failed;
    const std::string reason = r.value("reason", "");
    EXPECT_LE(reason.size(), 8000u) << reason.substr(0, 400);
    EXPECT_NE(reason.find("bytes in all"), std::string::npos) << reason.substr(0, 400);
  }
  EXPECT_EQ(failed, 3) << o.output.substr(0, 4000);
  std::printf("50 MiB data URI run: exit %d, peak %ld MiB, folder %ju bytes, output %zu bytes\n",
              o.exit_code, o.max_rss_kib >> 10, folder, o.output.size());
  fs::remove_all(dir, ec);
}

}  // namespace
