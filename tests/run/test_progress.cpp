#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "run/progress.h"

namespace sb {

using run::Progress;

namespace {

std::string contents(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string s;
  for (int c = std::fgetc(f); c != EOF; c = std::fgetc(f)) s += char(c);
  return s;
}

TEST(Progress, FormatsDurations) {
  EXPECT_EQ(Progress::format_duration(0.4), "0s");
  EXPECT_EQ(Progress::format_duration(42.0), "42s");
  EXPECT_EQ(Progress::format_duration(185.0), "3m05s");
  EXPECT_EQ(Progress::format_duration(3720.0), "1h02m");
  EXPECT_EQ(Progress::format_duration(-3.0), "0s");
}

TEST(Progress, EtaIsTheMeanJobTimeTimesWhatIsLeft) {
  EXPECT_FALSE(Progress::eta_seconds(0, 10, 5.0).has_value());
  EXPECT_DOUBLE_EQ(*Progress::eta_seconds(4, 6, 20.0), 30.0);
  EXPECT_DOUBLE_EQ(*Progress::eta_seconds(3, 0, 9.0), 0.0);
}

TEST(Progress, LineNamesTheJobAndCountsResumedJobsAsDone) {
  Progress p(nullptr, false, 10);
  p.add_done_without_running(3);  // resumed: done, but not in the rate
  p.start_job("jeep/count=4", "800x600", "pcss");
  EXPECT_EQ(p.line(10.0), "[4/10] jeep/count=4 @ 800x600  pcss  ETA --");
  p.finish_job();
  p.start_job("jeep/count=4", "800x600", "vsm");
  // One job ran in 10 s; 6 are left.
  EXPECT_EQ(p.line(10.0), "[5/10] jeep/count=4 @ 800x600  vsm  ETA 1m00s");
}

TEST(Progress, DrawsOnlyWhenEnabledAndClearsItsLine) {
  std::FILE* tty = std::tmpfile();
  std::FILE* pipe = std::tmpfile();
  ASSERT_NE(tty, nullptr);
  ASSERT_NE(pipe, nullptr);
  Progress on(tty, true, 2), off(pipe, false, 2);
  for (Progress* p : {&on, &off}) {
    p->start_job("s", "8x8", "t");
    p->clear();
    p->finish_job();
  }
  const std::string drawn = contents(tty);
  EXPECT_NE(drawn.find("[1/2] s @ 8x8  t  ETA --"), std::string::npos);
  EXPECT_NE(drawn.rfind("\r\033[2K"), std::string::npos);
  EXPECT_EQ(contents(pipe), "");  // not a terminal (or --quiet): silent
  std::fclose(tty);
  std::fclose(pipe);
}

}  // namespace
}  // namespace sb
