// The session a `run` process names in its records (run/session_info.h):
// /proc/loadavg's first figure, and an id of 16 hex digits drawn afresh for
// every session.
#include <gtest/gtest.h>

#include <cctype>
#include <string>

#include "run/session_info.h"

namespace sb::test {

using run::loadavg_one_minute;
using run::start_session;

TEST(SessionInfo, TheLoadAverageIsLoadavgsFirstFigure) {
  EXPECT_EQ(loadavg_one_minute("0.52 0.58 0.59 1/189 4242\n"), 0.52);
  EXPECT_EQ(loadavg_one_minute("12.00 7.31 3.10 5/900 77"), 12.0);
  EXPECT_EQ(loadavg_one_minute("3\n"), 3.0);
}

TEST(SessionInfo, ALoadavgThatDoesNotStartWithANumberHasNone) {
  EXPECT_FALSE(loadavg_one_minute(""));
  EXPECT_FALSE(loadavg_one_minute("busy 0.5 0.5"));
  EXPECT_FALSE(loadavg_one_minute("0.5x 0.5 0.5"));
  EXPECT_FALSE(loadavg_one_minute("-1 0 0"));
  EXPECT_FALSE(loadavg_one_minute("nan 0 0"));
}

TEST(SessionInfo, EachSessionHasItsOwnIdOfSixteenHexDigits) {
  const auto a = start_session(), b = start_session();
  EXPECT_NE(a.id, b.id);  // 2^-64 apart
  for (const auto* s : {&a, &b}) {
    ASSERT_EQ(s->id.size(), 16u) << s->id;
    for (char c : s->id) EXPECT_TRUE(std::isxdigit(static_cast<unsigned char>(c))) << s->id;
    EXPECT_EQ(s->started.size(), 20u) << s->started;  // 2026-12-07T12:00:00Z
    EXPECT_EQ(s->started.back(), 'Z');
    EXPECT_FALSE(s->host.empty());
    EXPECT_GE(s->load_average, 0.0);
  }
}

}  // namespace sb::test
