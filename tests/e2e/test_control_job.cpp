// The control job (frames.control, docs/ci.md): its frames are timed next to
// every job's, the record keeps both and their per-frame ratio, and it
// changes nothing that a job measures.
#include <gtest/gtest.h>

#include <cstdlib>

#include "e2e_util.h"
#include "run/injected_delay.h"

namespace sb::test {

using run::kInjectDelayVariable;

namespace {

using json = nlohmann::json;

json control_config(const json& frames) {
  return {{"name", "control"},
          {"scenes", {small_scene(2.0)}},
          {"techniques", {"none", {{"name", "pcf_box"}, {"params", {{"k", 3}, {"size", 256}}}}}},
          {"resolutions", {{64, 48}}},
          {"frames", frames},
          {"reference", {{"spp", 16}}}};
}

TEST(ControlJob, EveryTimedFrameHasAControlFrameAndTheRatioIsTheirQuotient) {
  const auto out = run_config(control_config({{"warmup", 1}, {"timed", 5}}), "control_pairs");
  ASSERT_EQ(out.records.size(), 2u);
  for (const auto& r : out.records) {
    ASSERT_EQ(r["status"], "ok") << r.dump();
    const json& t = r["timing"];
    ASSERT_TRUE(t.contains("control")) << t.dump();
    EXPECT_EQ(t["control"]["technique"], "none");
    const auto frame = t["frame"]["samples_ms"].get<std::vector<double>>();
    const auto control = t["control"]["frame"]["samples_ms"].get<std::vector<double>>();
    const auto ratio = t["control"]["frame_ratio"]["samples"].get<std::vector<double>>();
    ASSERT_EQ(frame.size(), 5u);
    ASSERT_EQ(control.size(), 5u);
    ASSERT_EQ(ratio.size(), 5u);
    for (size_t i = 0; i < 5; ++i) {
      EXPECT_GT(control[i], 0.0);
      EXPECT_NEAR(ratio[i], frame[i] / control[i], 1e-9 * ratio[i]) << i;
    }
  }
}

TEST(ControlJob, TheControlChangesNoMeasuredNumberAndNullTurnsItOff) {
  // Five timed frames end on a control frame (ABBA): the job's V must still
  // be the one measured.
  const auto with = run_config(control_config({{"warmup", 0}, {"timed", 5}}), "control_on");
  const auto without = run_config(
      control_config({{"warmup", 0}, {"timed", 5}, {"control", nullptr}}), "control_off");
  ASSERT_EQ(with.records.size(), without.records.size());
  for (size_t i = 0; i < with.records.size(); ++i) {
    const json& a = with.records[i];
    const json& b = without.records[i];
    ASSERT_EQ(a["job_id"], b["job_id"]);
    EXPECT_EQ(a["metrics"], b["metrics"]) << a["job_id"];
    EXPECT_EQ(a["visibility_check"], b["visibility_check"]);
    EXPECT_TRUE(a["timing"].contains("control"));
    EXPECT_FALSE(b["timing"].contains("control"));
  }
  // And pcf_box's V is its own, not the control's (none: lit everywhere).
  EXPECT_NE(with.record("pcf_box/k=3,size=256")["metrics"]["visibility"]["all"]["rmse"],
            with.record("none")["metrics"]["visibility"]["all"]["rmse"]);
}

TEST(ControlJob, AnInjectedDelayIsInTheJobsOwnTimeAndSaidInItsRecord) {
  ::setenv(kInjectDelayVariable, "pcf_box/k=3,size=256@25", 1);
  const auto out = run_config(control_config({{"warmup", 0}, {"timed", 3}}), "control_delay");
  ::unsetenv(kInjectDelayVariable);
  const json& slowed = out.record("pcf_box/k=3,size=256");
  EXPECT_GE(slowed["timing"]["technique"]["min_ms"].get<double>(), 25.0);
  EXPECT_GE(slowed["timing"]["frame"]["min_ms"].get<double>(), 25.0);
  ASSERT_TRUE(slowed.contains("warnings"));
  EXPECT_NE(slowed["warnings"].dump().find("SHADOWBENCH_INJECT_DELAY"), std::string::npos);
  // The control's frames next to it are not slowed, nor is another job.
  EXPECT_LT(slowed["timing"]["control"]["frame"]["min_ms"].get<double>(),
            slowed["timing"]["frame"]["min_ms"].get<double>());
  EXPECT_FALSE(out.record("none").contains("warnings"));
}

TEST(ControlJob, ARelativeDelayMakesEveryFrameThatMuchLonger) {
  // 100 %: the busy-wait lasts as long as the frame before it, so it is
  // half of every timed frame, and it counts in the technique's time.
  ::setenv(kInjectDelayVariable, "pcf_box/k=3,size=256@100%", 1);
  const auto out = run_config(control_config({{"warmup", 0}, {"timed", 4}}), "control_relative");
  ::unsetenv(kInjectDelayVariable);
  const json& t = out.record("pcf_box/k=3,size=256")["timing"];
  const auto frame = t["frame"]["samples_ms"].get<std::vector<double>>();
  const auto technique = t["technique"]["samples_ms"].get<std::vector<double>>();
  ASSERT_EQ(frame.size(), 4u);
  for (size_t i = 0; i < frame.size(); ++i) EXPECT_GE(technique[i], 0.5 * frame[i] - 0.05) << i;
}

}  // namespace
}  // namespace sb::test
