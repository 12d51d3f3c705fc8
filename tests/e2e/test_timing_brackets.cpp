// What the timed frames may contain: a technique's first frame (shader
// compilation, first-use driver work) is never timed, even with "warmup": 0.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "config/experiment.h"
#include "core/registry.h"
#include "gl/gl.h"
#include "results/store.h"
#include "run/runner.h"

namespace sb::test {
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
  const Experiment e = parse_experiment(config, "brackets.json", registry);
  RunOptions o;
  o.run_dir = (std::filesystem::temp_directory_path() / "shadowbench_e2e_brackets").string();
  std::filesystem::remove_all(o.run_dir);
  o.run_id = "brackets";
  o.cache_dir = "";
  o.quiet = true;
  o.write_images = false;
  ASSERT_EQ(run_experiment(e, o).ok, 1);
  EXPECT_EQ(calls, 4) << "one compile frame, then the three timed ones";
  const auto records = read_run_records(o.run_dir);
  ASSERT_EQ(records.size(), 1u);
  const auto& timing = records[0]["timing"];
  EXPECT_EQ(timing["compile_frames"], 1);
  EXPECT_EQ(timing["technique"]["count"], 3);
  // A sample holding the first frame would be at least its 400 ms sleep.
  EXPECT_LT(timing["technique"]["max_ms"].get<double>(), 400.0);
}

}  // namespace
}  // namespace sb::test
