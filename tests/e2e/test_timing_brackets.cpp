// What the timed frames may contain: a technique's first frame (shader
// compilation, first-use driver work) is never timed, even with "warmup": 0;
// and a technique is one timing bracket, whatever its number of passes, so a
// many-pass technique pays no more syncs than a single-pass one.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "../config/cli_runner.h"
#include "config/experiment.h"
#include "e2e_util.h"
#include "gl/context.h"
#include "gl/gl.h"
#include "plugin/registry.h"
#include "run/runner.h"
#include "store/results_store.h"

namespace sb::test {

using config::Experiment;
using config::parse_experiment;
using core::Params;
using plugin::FrameInputs;
using plugin::Needs;
using plugin::Registry;
using plugin::Technique;
using run::run_experiment;
using run::RunOptions;
using store::read_run_records;

namespace {

// Slow on its first frame only, as a technique whose shaders compile lazily.
class SlowFirstFrame final : public Technique {
 public:
  explicit SlowFirstFrame(int* calls) : calls_(calls) {}
  void prepare(const FrameInputs& /*in*/) override {}
  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    auto pass = timer.scope("work");
    if ((*calls_)++ == 0) std::this_thread::sleep_for(std::chrono::milliseconds(400));
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glClearColor(1, 1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
  }

 private:
  int* calls_;
};

TEST(TimingBrackets, TheFirstFrameIsNeverTimedEvenWithoutWarmup) {
  int calls = 0;
  Registry registry;
  registry.add(
      {"slow_first", "test", "slow on its first frame", Needs{}, {}, [&calls](const Params&) {
         return std::make_unique<SlowFirstFrame>(&calls);
       }});
  const nlohmann::json config = {{"name", "brackets"},
                                 {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 2}}}}}},
                                 {"techniques", {"slow_first"}},
                                 {"resolutions", {{32, 24}}},
                                 {"frames", {{"warmup", 0}, {"timed", 3}}},
                                 {"reference", {{"spp", 4}}}};
  const auto out = run_with_registry(config, registry, "brackets");
  ASSERT_EQ(out.summary.ok, 1);
  EXPECT_EQ(calls, 4) << "one compile frame, then the three timed ones";
  const auto& records = out.records;
  ASSERT_EQ(records.size(), 1u);
  const auto& timing = records[0]["timing"];
  EXPECT_EQ(timing["compile_frames"], 1);
  EXPECT_EQ(timing["technique"]["count"], 3);
  // A sample holding the first frame would be at least its 400 ms sleep.
  EXPECT_LT(timing["technique"]["max_ms"].get<double>(), 400.0);
}

// `passes` named passes, each a clear of the visibility target.
class ManyPasses final : public Technique {
 public:
  explicit ManyPasses(int passes) : passes_(passes) {}
  void prepare(const FrameInputs& /*in*/) override {}
  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    for (int i = 0; i < passes_; ++i) {
      auto pass = timer.scope("pass" + std::to_string(i));
      glClearColor(1, 1, 1, 1);
      glClear(GL_COLOR_BUFFER_BIT);
    }
  }

 private:
  int passes_;
};

TEST(TimingBrackets, CoarseDetailTimesTheHarnessBracketOnlyWhateverThePassCount) {
  const auto context = gl::create_context(gl::Backend::OSMesa);
  gl::PassTimer coarse(gl::TimingSource::CpuFinish, gl::PassDetail::Coarse);
  coarse.begin_frame();
  {
    auto technique = coarse.bracket("technique");
    for (int i = 0; i < 40; ++i) auto pass = coarse.scope("pass" + std::to_string(i));
  }
  const auto frame = coarse.end_frame();
  ASSERT_EQ(frame.passes.size(), 1u);
  EXPECT_EQ(frame.passes[0].first, "technique");
  // Fine: the passes are the brackets; they may not nest in another.
  gl::PassTimer fine(gl::TimingSource::CpuFinish, gl::PassDetail::Fine);
  fine.begin_frame();
  for (int i = 0; i < 40; ++i) auto pass = fine.scope("pass" + std::to_string(i));
  EXPECT_EQ(fine.end_frame().passes.size(), 40u);
  fine.begin_frame();
  auto outer = fine.bracket("technique");
  EXPECT_THROW(fine.scope("inner"), std::logic_error);
}

Experiment many_passes_experiment(Registry& registry) {
  registry.add({"many_passes", "test", "forty passes", Needs{}, {}, [](const Params&) {
                  return std::make_unique<ManyPasses>(40);
                }});
  const nlohmann::json config = {{"name", "many_passes"},
                                 {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 2}}}}}},
                                 {"techniques", {"many_passes"}},
                                 {"resolutions", {{32, 24}}},
                                 {"frames", {{"warmup", 1}, {"timed", 3}}},
                                 {"reference", {{"spp", 4}}}};
  return parse_experiment(config, "many_passes.json", registry);
}

TEST(TimingBrackets, FinePassTimingRunsInFramesOfItsOwn) {
  Registry registry;
  const Experiment e = many_passes_experiment(registry);
  for (const auto detail : {gl::PassDetail::Coarse, gl::PassDetail::Fine}) {
    RunOptions o;
    o.run_dir = fresh_test_folder("shadowbench_e2e_") + "/" + gl::to_string(detail);
    o.run_id = "many_passes";
    o.cache_dir = "";
    o.quiet = true;
    o.write_images = false;
    o.pass_detail = detail;
    ASSERT_EQ(run_experiment(e, o).ok, 1);
    const auto timing = read_run_records(o.run_dir).at(0)["timing"];
    EXPECT_EQ(timing["pass_timing"], gl::to_string(detail));
    EXPECT_EQ(timing["technique"]["count"], 3);
    if (detail == gl::PassDetail::Coarse) {
      EXPECT_FALSE(timing.contains("passes"));
      EXPECT_FALSE(timing.contains("fine"));
      continue;
    }
    // Every pass, each with its own samples from the extra frames.
    EXPECT_EQ(timing["pass_order"].size(), 40u);
    EXPECT_EQ(timing["passes"]["pass39"]["samples_ms"].size(), 3u);
    EXPECT_EQ(timing["fine"]["frames"], 3);
    double sum = 0.0;
    for (const auto& [name, stats] : timing["passes"].items())
      sum += stats["samples_ms"][0].get<double>();
    EXPECT_NEAR(timing["fine"]["technique"]["samples_ms"][0].get<double>(), sum, 1e-9);
  }
}

TEST(TimingBrackets, ThePassTimingOptionIsParsedAndRecorded) {
  const std::string dir = fresh_test_folder("shadowbench_test_pass_timing_");
  const std::string config = dir + "/c.json";
  std::ofstream(config)
      << R"({"name":"p","scenes":[{"type":"sphere_grid","params":{"grid":2}}],)"
      << R"("techniques":["shadow_map"],"resolutions":[[32,24]],)"
      << R"("frames":{"warmup":0,"timed":2},"reference":{"spp":4,"cache":false}})";
  const auto bad = run_cli("run " + config + " --pass-timing medium --out " + dir + "/bad");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("--pass-timing"), std::string::npos) << bad.output;
  const auto ok = run_cli("run " + config + " --quiet --pass-timing fine --out " + dir + "/ok");
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  const auto timing = read_run_records(dir + "/ok").at(0)["timing"];
  EXPECT_EQ(timing["pass_timing"], "fine");
  EXPECT_EQ(timing["pass_order"], nlohmann::json::array({"shadow_map", "lookup"}));
}

}  // namespace
}  // namespace sb::test
