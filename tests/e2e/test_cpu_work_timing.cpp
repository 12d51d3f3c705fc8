// A technique's CPU work counts in its time on both kinds of bracket: CPU
// clocks (llvmpipe) and GL timestamps (GPUs). There is no GPU here, so the
// GPUs' path is forced on llvmpipe (RunOptions::timing_source); a technique
// that only burns a known stretch of CPU time must be charged at least that.
// Loose bounds only (0.8 of a known burn, ratios of 0.5 and 0.25 against the
// CPU clock's time of the same work): the machine is shared and noisy.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>

#include "config/experiment.h"
#include "e2e_util.h"
#include "gl/context.h"
#include "gl/gl.h"
#include "gl/pass_timer.h"
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

constexpr double kBurnMs = 40.0;
// What a bracket around the burn must at least report.
constexpr double kAtLeastMs = 0.8 * kBurnMs;

// Keeps this thread's core busy for `ms`, without a GL call.
void burn_cpu(double ms) {
  using Clock = std::chrono::steady_clock;
  const auto end = Clock::now() + std::chrono::duration<double, std::milli>(ms);
  volatile double sink = 0.0;
  while (Clock::now() < end) sink = sink + 1.0;
}

// CPU work in a pass of its own (as CPU silhouettes or a reconstruction),
// then the one GL command it needs: V = 1 everywhere.
class CpuBurn final : public Technique {
 public:
  void prepare(const FrameInputs& /*in*/) override {}
  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    {
      auto pass = timer.scope("burn");
      burn_cpu(kBurnMs);
    }
    auto pass = timer.scope("clear");
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glClearColor(1, 1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
  }
};

TEST(CpuWorkTiming, BothKindsOfBracketCountTheCpuWorkInsideThem) {
  const auto context = gl::create_context(gl::Backend::OSMesa);
  ASSERT_TRUE(gl::timestamp_queries_supported());
  for (const auto source : {gl::TimingSource::CpuFinish, gl::TimingSource::GpuQuery}) {
    gl::PassTimer timer(source, gl::PassDetail::Coarse);
    timer.begin_frame();
    {
      auto technique = timer.bracket("technique");
      burn_cpu(kBurnMs);
    }
    const auto frame = timer.end_frame();
    ASSERT_EQ(frame.passes.size(), 1u);
    EXPECT_GE(frame.passes[0].second, kAtLeastMs) << gl::to_string(source);
    EXPECT_LE(frame.passes[0].second, frame.total_ms) << gl::to_string(source);
  }
}

// GL work: scissored clears (each one binned and run tile by tile, where a
// full clear would only replace the previous one) of a 2048² RGBA32F
// target, some 20 ms on llvmpipe.
void clear_tiles(GLuint framebuffer) {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glEnable(GL_SCISSOR_TEST);
  for (int i = 0; i < 8; ++i) {
    glScissor(i, 0, 2048 - i, 2048);
    glClearColor(static_cast<float>(i), 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  glDisable(GL_SCISSOR_TEST);
}

double median_of_3(std::array<double, 3> v) {
  std::sort(v.begin(), v.end());
  return v[1];
}

// GL timestamps are right on llvmpipe (its GL_TIME_ELAPSED is not), so the
// GPUs' path can be checked against the CPU clock's here: the bracket that
// issues the clears counts them to their end, though it returns before the
// rasteriser has run them, and the next bracket does not count them again.
TEST(CpuWorkTiming, ATimestampBracketCountsItsGlWorkToItsEndAndOnlyOnce) {
  const auto context = gl::create_context(gl::Backend::OSMesa);
  GLuint texture = 0, framebuffer = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_RGBA32F, 2048, 2048);
  glCreateFramebuffers(1, &framebuffer);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
  std::array<double, 3> cpu_clears{}, stamped_clears{}, stamped_after{};
  for (size_t rep = 0; rep < 3; ++rep)
    for (const auto source : {gl::TimingSource::CpuFinish, gl::TimingSource::GpuQuery}) {
      gl::PassTimer timer(source, gl::PassDetail::Coarse);
      timer.begin_frame();
      {
        auto bracket = timer.bracket("clears");
        clear_tiles(framebuffer);
      }
      { auto bracket = timer.bracket("after"); }
      const auto frame = timer.end_frame();
      ASSERT_EQ(frame.passes.size(), 2u);
      if (source == gl::TimingSource::CpuFinish) {
        cpu_clears[rep] = frame.passes[0].second;
      } else {
        stamped_clears[rep] = frame.passes[0].second;
        stamped_after[rep] = frame.passes[1].second;
      }
    }
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteTextures(1, &texture);
  const double clears = median_of_3(cpu_clears);
  EXPECT_GE(median_of_3(stamped_clears), 0.5 * clears);
  EXPECT_LT(median_of_3(stamped_after), 0.25 * clears);
}

TEST(CpuWorkTiming, ATechniquesCpuWorkCountsInItsTimeWithTimestampBrackets) {
  Registry registry;
  registry.add({"cpu_burn", "test", "40 ms of CPU work a frame", Needs{}, {}, [](const Params&) {
                  return std::make_unique<CpuBurn>();
                }});
  const nlohmann::json config = {{"name", "cpu_burn"},
                                 {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 2}}}}}},
                                 {"techniques", {"cpu_burn"}},
                                 {"resolutions", {{32, 24}}},
                                 {"frames", {{"warmup", 0}, {"timed", 2}}},
                                 {"reference", {{"spp", 4}}}};
  const Experiment e = parse_experiment(config, "cpu_burn.json", registry);
  RunOptions o;
  o.run_dir = fresh_test_folder("shadowbench_e2e_");
  o.run_id = "cpu_burn";
  o.cache_dir = "";
  o.quiet = true;
  o.write_images = false;
  o.pass_detail = gl::PassDetail::Fine;
  o.timing_source = gl::TimingSource::GpuQuery;
  ASSERT_EQ(run_experiment(e, o).ok, 1);
  const auto record = read_run_records(o.run_dir).at(0);
  EXPECT_EQ(record["timing_source"], "gl_timestamp_query");
  const auto& timing = record["timing"];
  // The technique's one bracket, and the burn's own in the fine frames.
  for (const auto* series : {&timing["technique"], &timing["passes"]["burn"]}) {
    ASSERT_EQ((*series)["samples_ms"].size(), 2u);
    for (const auto& ms : (*series)["samples_ms"]) EXPECT_GE(ms.get<double>(), kAtLeastMs);
  }
  // The frame holds the technique: its own brackets never add up to more.
  for (size_t i = 0; i < 2; ++i)
    EXPECT_LE(timing["technique"]["samples_ms"][i].get<double>(),
              timing["frame"]["samples_ms"][i].get<double>());
}

}  // namespace
}  // namespace sb::test
