// The test-only trace of when the run's processes wrote and timed frames
// (run/io_trace.h): one clock, whole lines, and a slow disk that is slow.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/error.h"
#include "run/io_trace.h"

namespace sb {

using core::InputError;
using run::io_trace_enabled;
using run::kIoTraceVariable;
using run::kSlowParentIoVariable;
using run::monotonic_ns;
using run::ParentIoSpan;
using run::slow_parent_io_ns;
using run::write_trace;

namespace {

namespace fs = std::filesystem;

fs::path fresh_trace(const std::string& name) {
  fs::path file = fs::temp_directory_path() / ("shadowbench_io_trace_" + name + ".txt");
  fs::remove(file);
  ::setenv(kIoTraceVariable, file.c_str(), 1);
  return file;
}

std::vector<std::string> lines(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

class IoTrace : public ::testing::Test {
 protected:
  void TearDown() override {
    ::unsetenv(kIoTraceVariable);
    ::unsetenv(kSlowParentIoVariable);
  }
};

TEST_F(IoTrace, IsOffAndWritesNothingWithoutTheVariable) {
  ::unsetenv(kIoTraceVariable);
  EXPECT_FALSE(io_trace_enabled());
  ::setenv(kSlowParentIoVariable, "500", 1);
  EXPECT_EQ(slow_parent_io_ns(), 0);  // the slow disk only with the trace on
  const auto t0 = monotonic_ns();
  { const ParentIoSpan span("record x", true); }
  EXPECT_LT(monotonic_ns() - t0, 400'000'000);
}

TEST_F(IoTrace, AppendsOneLinePerSpanWithPidParentKindAndTimes) {
  const fs::path file = fresh_trace("lines");
  ASSERT_TRUE(io_trace_enabled());
  write_trace({{"timed", "pcss frame 3", 10, 20}, {"timed", "pcss frame 4", 20, 35}});
  const auto before = monotonic_ns();
  { const ParentIoSpan span("record a"); }
  const auto after = monotonic_ns();
  const auto got = lines(file);
  ASSERT_EQ(got.size(), 3u);
  const std::string me = std::to_string(::getpid()) + " " + std::to_string(::getppid()) + " ";
  EXPECT_EQ(got[0], me + "timed 10 20 pcss frame 3");
  EXPECT_EQ(got[1], me + "timed 20 35 pcss frame 4");
  std::istringstream io(got[2]);
  long pid = 0, parent = 0;
  long long begin = 0, end = 0;
  std::string kind, what;
  io >> pid >> parent >> kind >> begin >> end >> what;
  EXPECT_EQ(kind, "parent-io");
  EXPECT_LE(before, begin);
  EXPECT_LE(begin, end);
  EXPECT_LE(end, after);
  EXPECT_EQ(what, "record");
}

TEST_F(IoTrace, ASlowDiskMakesAStoredRecordLastAtLeastItsMilliseconds) {
  const fs::path file = fresh_trace("slow");
  ::setenv(kSlowParentIoVariable, "30", 1);
  EXPECT_EQ(slow_parent_io_ns(), 30'000'000);
  { const ParentIoSpan span("record a", true); }
  { const ParentIoSpan span("log"); }  // not a record: not slowed
  const auto got = lines(file);
  ASSERT_EQ(got.size(), 2u);
  long long begin = 0, end = 0;
  std::string skip;
  std::istringstream(got[0]) >> skip >> skip >> skip >> begin >> end;
  EXPECT_GE(end - begin, 30'000'000);
  std::istringstream(got[1]) >> skip >> skip >> skip >> begin >> end;
  EXPECT_LT(end - begin, 30'000'000);
}

TEST_F(IoTrace, AMalformedSlowDiskIsBadInputNamingTheVariable) {
  fresh_trace("bad");
  for (const char* bad : {"x", "-1", "0", "5ms", "nan", "1e9"}) {
    ::setenv(kSlowParentIoVariable, bad, 1);
    try {
      slow_parent_io_ns();
      ADD_FAILURE() << bad << ": accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(kSlowParentIoVariable), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace sb
