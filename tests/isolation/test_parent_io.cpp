// No write of the parent's overlaps a timed frame (docs/robustness.md, "The
// parent's writes and the timed frames"): neither in a run whose jobs render
// in a child process, nor under compare-builds, where the other build's
// parent writes too. Every process appends its spans to one trace
// (run/io_trace.h), and storing a record is slowed to a slow disk's pace,
// so that a write that can overlap a frame does.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "isolation_util.h"

namespace sb::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

struct Span {
  long pid = 0, parent = 0;
  std::string kind, what;
  long long begin_ns = 0, end_ns = 0;
};

std::vector<Span> read_trace(const fs::path& file) {
  std::vector<Span> spans;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    Span s;
    fields >> s.pid >> s.parent >> s.kind >> s.begin_ns >> s.end_ns;
    std::getline(fields >> std::ws, s.what);
    EXPECT_FALSE(fields.fail() && s.what.empty()) << "a torn trace line: " << line;
    EXPECT_LE(s.begin_ns, s.end_ns) << line;
    spans.push_back(s);
  }
  return spans;
}

size_t count(const std::vector<Span>& spans, const std::string& kind, const std::string& what) {
  size_t n = 0;
  for (const Span& s : spans) n += s.kind == kind && s.what.rfind(what, 0) == 0 ? 1 : 0;
  return n;
}

// Every parent-io span against every timed span, of any process: the
// parent's own children's and, under compare-builds, the other build's.
void expect_no_parent_io_in_a_timed_frame(const std::vector<Span>& spans) {
  for (const Span& io : spans) {
    if (io.kind != "parent-io") continue;
    for (const Span& frame : spans)
      if (frame.kind == "timed" && io.begin_ns < frame.end_ns && frame.begin_ns < io.end_ns)
        ADD_FAILURE() << (frame.parent == io.pid ? "" : "another build's frame: ") << "process "
                      << io.pid << "'s \"" << io.what << "\" [" << io.begin_ns / 1000 << ", "
                      << io.end_ns / 1000 << "] us overlaps process " << frame.pid << "'s \""
                      << frame.what << "\" [" << frame.begin_ns / 1000 << ", "
                      << frame.end_ns / 1000 << "] us";
  }
}

// `n` jobs of the test-only fault plugin, each frame 10 ms: no shader to
// compile, so each next job's frames would start while the parent is still
// storing the record before, at 300 ms a record.
json quick_jobs(int n) {
  json slow_ms = json::array();
  for (int i = 0; i < n; ++i) slow_ms.push_back(10 + i);
  return small_experiment(json::array({{{"name", "fault"}, {"params", {{"slow_ms", slow_ms}}}}}));
}

std::string traced(const fs::path& trace, const std::string& args) {
  return "SHADOWBENCH_IO_TRACE='" + trace.string() + "' SHADOWBENCH_SLOW_PARENT_IO=300 " +
         shadowbench_command(args);
}

TEST(ParentIo, NoParentWriteOverlapsATimedFrameOfItsChild) {
  const auto dir = test_folder();
  const auto file = write_config(dir, quick_jobs(5));
  const fs::path trace = dir / "trace.txt";
  const CliRun r = run_command(traced(trace, "run " + file + " --out " + (dir / "run").string() +
                                                 " --isolation group --no-cache --no-images"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto spans = read_trace(trace);
  // Not vacuous: every job's timed frames and every record's write are there.
  EXPECT_EQ(count(spans, "timed", ""), 5u * 2u);
  EXPECT_EQ(count(spans, "parent-io", "record "), 5u);
  expect_no_parent_io_in_a_timed_frame(spans);
}

TEST(ParentIo, NoParentWriteOverlapsATimedFrameOfEitherBuildUnderCompareBuilds) {
  const auto dir = test_folder();
  const auto file = write_config(dir, quick_jobs(3));
  const fs::path trace = dir / "trace.txt";
  const std::string out = (dir / "out").string();
  const CliRun r = run_command(
      traced(trace, "compare-builds --base '" SHADOWBENCH_EXE "' --new '" SHADOWBENCH_EXE "' " +
                        file + " --out " + out + " --turn-block 1 --no-cache"));
  EXPECT_NE(r.output.find("base: " + out + "/base, 7 turns, exit code 0"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("new: " + out + "/new, 7 turns, exit code 0"), std::string::npos)
      << r.output;
  const auto spans = read_trace(trace);
  EXPECT_EQ(count(spans, "timed", ""), 2u * 3u * 2u);
  EXPECT_EQ(count(spans, "parent-io", "record "), 2u * 3u);
  expect_no_parent_io_in_a_timed_frame(spans);
}

}  // namespace
}  // namespace sb::test
