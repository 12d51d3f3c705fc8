// A technique that makes a GL error fails its own job with the driver's
// message; the other jobs of the run still finish and keep their records.
#include <gtest/gtest.h>

#include <filesystem>

#include "config/experiment.h"
#include "core/error.h"
#include "e2e_util.h"
#include "gl/gl.h"
#include "plugin/registry.h"
#include "results/store.h"
#include "run/runner.h"

namespace sb::test {
namespace {

class MakesAGlError final : public Technique {
 public:
  void prepare(const FrameInputs& /*in*/) override {}
  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    auto pass = timer.scope("broken");
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glEnable(0x1234);  // not a capability: GL_INVALID_ENUM
  }
};

class Throws final : public Technique {
 public:
  void prepare(const FrameInputs& /*in*/) override { throw JobError("cannot prepare"); }
  void render(const FrameInputs& /*in*/, gl::PassTimer& /*timer*/) override {}
};

TEST(Failures, AFailingJobLeavesTheOthersIntact) {
  Registry registry;
  registry.load_plugins(SHADOWBENCH_PLUGIN_DIR);
  registry.add({"gl_error", "test", "makes GL_INVALID_ENUM", Needs{}, {}, [](const Params&) {
                  return std::make_unique<MakesAGlError>();
                }});
  registry.add({"throws", "test", "throws in prepare", Needs{}, {}, [](const Params&) {
                  return std::make_unique<Throws>();
                }});
  const nlohmann::json config = {{"name", "failures"},
                                 {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 2}}}}}},
                                 {"techniques", {"none", "gl_error", "throws", "shadow_map"}},
                                 {"resolutions", {{32, 24}}},
                                 {"frames", {{"warmup", 0}, {"timed", 1}}},
                                 {"reference", {{"spp", 4}}}};
  const Experiment e = parse_experiment(config, "failures.json", registry);
  RunOptions o;
  o.run_dir = (std::filesystem::temp_directory_path() / "shadowbench_e2e_failures").string();
  std::filesystem::remove_all(o.run_dir);
  o.run_id = "failures";
  o.cache_dir = "";
  o.quiet = true;
  const RunSummary s = run_experiment(e, o);
  EXPECT_EQ(s.ok, 2);
  EXPECT_EQ(s.failed, 2);
  const auto records = read_run_records(o.run_dir);
  ASSERT_EQ(records.size(), 4u);
  EXPECT_EQ(records[0]["status"], "ok");
  EXPECT_EQ(records[1]["status"], "failed");
  const std::string reason = records[1]["reason"];
  EXPECT_NE(reason.find("gl_error compile frame"), std::string::npos) << reason;
  EXPECT_NE(reason.find("GL_INVALID_ENUM"), std::string::npos) << reason;
  EXPECT_EQ(records[2]["status"], "failed");
  EXPECT_EQ(records[2]["reason"], "cannot prepare");
  EXPECT_EQ(records[3]["status"], "ok") << records[3].dump();
}

TEST(Failures, ABadSceneFileFailsItsJobsAndCountsAsBadInput) {
  const nlohmann::json config = {
      {"name", "bad_scene"},
      {"scenes",
       {{{"type", "gltf"},
         {"params",
          {{"file", SHADOWBENCH_SOURCE_DIR "/tests/gltf/corpus/index_out_of_range.gltf"}}}},
        {{"type", "sphere_grid"}, {"params", {{"grid", 2}}}}}},
      {"techniques", {"none"}},
      {"resolutions", {{16, 12}}},
      {"frames", {{"warmup", 0}, {"timed", 1}}},
      {"reference", {{"spp", 4}}}};
  const auto out = run_config(config, "bad_scene");
  EXPECT_EQ(out.summary.bad_input, 1);
  EXPECT_EQ(out.summary.failed, 1);
  EXPECT_EQ(out.summary.ok, 1);
  const std::string reason = out.records.at(0)["reason"];
  EXPECT_NE(reason.find("index_out_of_range.gltf: at accessor 1"), std::string::npos) << reason;
}

}  // namespace
}  // namespace sb::test
