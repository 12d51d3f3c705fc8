// Shards (plan/shards.h): every job of the plan in exactly one shard, the
// same split on every call, balanced by estimated cost, and "K/N" checked.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>

#include "../config/cli_runner.h"
#include "config/experiment.h"
#include "plan/plan.h"
#include "plan/shards.h"
#include "plugin/registry.h"
#include "test_registry.h"

namespace sb::test {

using config::Experiment;
using config::parse_experiment;
using plan::make_plan;
using plan::parse_shard;

namespace {

Experiment sweep() {
  // 2 scenes × 3 resolutions × 8 techniques, accumulation far costlier.
  return parse_experiment(nlohmann::json::parse(R"({
    "scenes": [{"type": "sphere_grid", "params": {"grid": [2, 3]}}],
    "techniques": ["none", "shadow_map", {"name": "pcf_box", "params": {"k": [3, 5, 7]}},
                   "pcss", {"name": "accumulation", "params": {"samples": [16, 64]}}],
    "resolutions": ["320x240", "640x480", "1280x720"]})"),
                          "sweep.json", registry());
}

TEST(Shards, EveryJobIsInExactlyOneShardInPlanOrder) {
  const Experiment e = sweep();
  const auto jobs = make_plan(e, 5).jobs;
  ASSERT_EQ(jobs.size(), 2u * 3u * 8u);
  std::set<std::string> ids;
  for (size_t i = 0; i < jobs.size(); ++i) {
    EXPECT_TRUE(ids.insert(jobs[i].id).second);
    EXPECT_GE(jobs[i].shard, 1);
    EXPECT_LE(jobs[i].shard, 5);
    // Plan order: scene-major, then resolution, then technique.
    EXPECT_EQ(i, (jobs[i].scene * 3 + jobs[i].resolution) * 8 + jobs[i].technique);
    EXPECT_EQ(jobs[i].index, i);
  }
}

TEST(Shards, TheSplitIsTheSameOnEveryCall) {
  const Experiment e = sweep();
  const auto a = make_plan(e, 4).jobs, b = make_plan(sweep(), 4).jobs;
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].shard, b[i].shard) << a[i].id;
}

TEST(Shards, ShardsAreBalancedWithinTheCostliestJob) {
  const Experiment e = sweep();
  for (int n : {2, 3, 4, 7}) {
    const auto jobs = make_plan(e, n).jobs;
    std::map<int, double> load;
    double costliest = 0;
    for (const auto& j : jobs) {
      load[j.shard] += j.cost;
      costliest = std::max(costliest, j.cost);
    }
    ASSERT_EQ(load.size(), size_t(n));
    double lo = 1e300, hi = 0;
    for (const auto& [shard, l] : load) {
      lo = std::min(lo, l);
      hi = std::max(hi, l);
    }
    // Greedy on sorted costs: no shard exceeds another by more than one job.
    EXPECT_LE(hi - lo, costliest) << n << " shards";
  }
}

TEST(Shards, CostGrowsWithPixelsAndTheTechniquesWeight) {
  const Experiment e = sweep();
  const auto jobs = make_plan(e, 1).jobs;
  const auto cost = [&](const std::string& res, const std::string& technique) {
    for (const auto& j : jobs)
      if (j.scene == 0 && e.resolutions[j.resolution].label() == res &&
          e.techniques[j.technique].name == technique)
        return j.cost;
    return -1.0;
  };
  EXPECT_DOUBLE_EQ(cost("320x240", "shadow_map"), 1.0 + 4.5 * 0.0768);
  EXPECT_GT(cost("1280x720", "shadow_map"), cost("640x480", "shadow_map"));
  // accumulation's weight is 1 + samples/8.
  EXPECT_DOUBLE_EQ(cost("320x240", "accumulation/samples=64"), 9.0 * (1.0 + 4.5 * 0.0768));
}

TEST(Shards, ShardSpecsAreChecked) {
  EXPECT_EQ(parse_shard("2/4").index, 2);
  EXPECT_EQ(parse_shard("2/4").count, 4);
  for (const char* bad : {"0/4", "5/4", "4", "a/b", "1/0", "1/10001", "-1/2", "1/2/3", "1.5/2"})
    EXPECT_THROW(parse_shard(bad), std::invalid_argument) << bad;
}

TEST(Shards, PlanPrintsTheLayout) {
  const auto r =
      run_cli("plan " + std::string(SHADOWBENCH_SOURCE_DIR) + "/configs/quick.json --shards 3");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("20 jobs in 3 shards"), std::string::npos) << r.output;
  for (const char* shard : {"shard 1/3: ", "shard 2/3: ", "shard 3/3: "})
    EXPECT_NE(r.output.find(shard), std::string::npos) << shard;
  const auto bad = run_cli("run x.json --shard 4/3");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("--shard: expected K/N"), std::string::npos) << bad.output;
}

}  // namespace
}  // namespace sb::test
