// SHADOWBENCH_INJECT_DELAY: the known slowdown that measures the CI gate.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>

#include "core/error.h"
#include "run/injected_delay.h"

namespace sb {

using core::InputError;
using run::InjectedDelay;
using run::kInjectDelayVariable;

namespace {

TEST(InjectedDelay, NamesTheVariantBeforeTheLastAtAndTheMillisecondsAfter) {
  const InjectedDelay d = InjectedDelay::parse("pcf_box/k=3,size=1024@2.5");
  EXPECT_TRUE(d.applies_to("pcf_box/k=3,size=1024"));
  EXPECT_FALSE(d.applies_to("pcf_box/k=5,size=1024"));
  EXPECT_FALSE(d.applies_to("pcf_box"));
  EXPECT_DOUBLE_EQ(d.milliseconds(40.0), 2.5);  // fixed, whatever the frame took
  EXPECT_NE(d.describe().find("SHADOWBENCH_INJECT_DELAY"), std::string::npos);
  EXPECT_NE(d.describe().find("not a measurement"), std::string::npos);
}

TEST(InjectedDelay, APercentIsAShareOfTheFramesOwnTime) {
  const InjectedDelay d = InjectedDelay::parse("pcf_box/k=3,size=1024@20%");
  EXPECT_TRUE(d.applies_to("pcf_box/k=3,size=1024"));
  EXPECT_DOUBLE_EQ(d.milliseconds(40.0), 8.0);
  EXPECT_DOUBLE_EQ(d.milliseconds(100.0), 20.0);
  EXPECT_NE(d.describe().find("20.0"), std::string::npos) << d.describe();
  EXPECT_NE(d.describe().find("% of the frame"), std::string::npos) << d.describe();
}

TEST(InjectedDelay, AMalformedValueIsBadInputNamingTheVariable) {
  for (const char* bad :
       {"pcf_box", "@3", "pcf_box@", "pcf_box@-1", "pcf_box@0", "pcf_box@2ms", "pcf_box@nan",
        "pcf_box@1e9", "pcf_box@%", "pcf_box@-5%", "pcf_box@5000%", "pcf_box@5%%"}) {
    try {
      InjectedDelay::parse(bad);
      ADD_FAILURE() << bad << ": accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("SHADOWBENCH_INJECT_DELAY"), std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

TEST(InjectedDelay, UnsetOrEmptyMeansNone) {
  ::unsetenv(kInjectDelayVariable);
  EXPECT_FALSE(InjectedDelay::from_environment().has_value());
  ::setenv(kInjectDelayVariable, "", 1);
  EXPECT_FALSE(InjectedDelay::from_environment().has_value());
  ::setenv(kInjectDelayVariable, "none@1", 1);
  ASSERT_TRUE(InjectedDelay::from_environment().has_value());
  EXPECT_TRUE(InjectedDelay::from_environment()->applies_to("none"));
  ::unsetenv(kInjectDelayVariable);
}

// A lower bound only: the wait is a fixed wall time, never shorter.
TEST(InjectedDelay, WaitsAtLeastTheGivenTime) {
  const InjectedDelay d = InjectedDelay::parse("x@20");
  const auto t0 = std::chrono::steady_clock::now();
  d.wait(1.0);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GE(ms, 20.0);
}

}  // namespace
}  // namespace sb
