// A technique that makes a GL error fails its own job with the driver's
// message; the other jobs of the run still finish and keep their records.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <utility>

#include "config/experiment.h"
#include "core/error.h"
#include "e2e_util.h"
#include "gl/gl.h"
#include "gl/objects.h"
#include "plugin/registry.h"
#include "run/runner.h"
#include "store/results_store.h"

namespace sb::test {

using config::Experiment;
using config::parse_experiment;
using core::JobError;
using core::Params;
using plugin::FrameInputs;
using plugin::Needs;
using plugin::Registry;
using plugin::Technique;
using plugin::TechniqueInfo;
using run::run_experiment;
using run::RunOptions;
using run::RunSummary;
using store::read_run_records;

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

// Fails mid-frame with the pipeline in a state no technique expects.
class FailsWithOddState final : public Technique {
 public:
  void prepare(const FrameInputs& /*in*/) override {}
  void render(const FrameInputs& /*in*/, gl::PassTimer& timer) override {
    // NOLINTNEXTLINE(clang-analyzer-deadcode.DeadStores): a scope, ended by the throw
    auto pass = timer.scope("odd_state");
    glEnable(GL_BLEND);
    glBlendEquation(GL_MAX);
    glBlendFunc(GL_ZERO, GL_ONE);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 1, 1);
    glStencilFunc(GL_NEVER, 1, 0xff);
    glStencilOp(GL_INVERT, GL_INVERT, GL_INVERT);
    glDepthFunc(GL_NEVER);
    glFrontFace(GL_CW);
    glCullFace(GL_FRONT);
    throw JobError("failed mid-frame");
  }
};

// Another technique, which then leaves behind the pixel-pack state a
// technique that reads its own data back might: a bound pack buffer, a row
// length, skips and alignment, and clamping on read.
class LeavesPixelStoreState final : public Technique {
 public:
  explicit LeavesPixelStoreState(std::unique_ptr<Technique> inner) : inner_(std::move(inner)) {}
  void prepare(const FrameInputs& in) override {
    inner_->prepare(in);
    pack_buffer_ = gl::make_buffer(64, nullptr, GL_DYNAMIC_STORAGE_BIT);
  }
  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    inner_->render(in, timer);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, pack_buffer_.get());
    glPixelStorei(GL_PACK_ROW_LENGTH, 7);
    glPixelStorei(GL_PACK_SKIP_ROWS, 3);
    glPixelStorei(GL_PACK_SKIP_PIXELS, 2);
    glPixelStorei(GL_PACK_ALIGNMENT, 8);
    glClampColor(GL_CLAMP_READ_COLOR, GL_TRUE);
  }

 private:
  std::unique_ptr<Technique> inner_;
  gl::Buffer pack_buffer_;
};

// The harness reads V back after the technique's last frame: pixel-store
// state it left behind must neither fail that read (a GL error in
// "read-back") nor shift or clamp what is read.
TEST(Failures, PixelStoreStateLeftByATechniqueDoesNotReachTheReadBack) {
  Registry registry;
  registry.load_plugins(SHADOWBENCH_PLUGIN_DIR);
  TechniqueInfo leaves = *registry.find("shadow_map");
  leaves.name = "shadow_map_leftovers";
  leaves.family = "test";
  leaves.create = [create = leaves.create](const Params& p) {
    return std::make_unique<LeavesPixelStoreState>(create(p));
  };
  registry.add(leaves);
  const nlohmann::json config = {
      {"name", "leftovers"},
      {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 2}, {"light_size", 2.0}}}}}},
      {"techniques", {"shadow_map_leftovers", "shadow_map"}},
      {"resolutions", {{40, 30}}},
      {"frames", {{"warmup", 0}, {"timed", 2}}},
      {"reference", {{"spp", 4}}}};
  const RunOutput out = run_with_registry(config, registry, "leftovers");
  ASSERT_EQ(out.records.size(), 2u);
  ASSERT_EQ(out.records[0]["status"], "ok") << out.records[0].dump();
  ASSERT_EQ(out.records[1]["status"], "ok") << out.records[1].dump();
  // Read whole and unshifted: the same V as shadow_map's, so the same errors.
  const auto& leftovers = out.records[0]["metrics"]["visibility"]["all"];
  const auto& clean = out.records[1]["metrics"]["visibility"]["all"];
  ASSERT_GT(clean["rmse"].get<double>(), 0.0);
  EXPECT_EQ(leftovers["pixel_count"], clean["pixel_count"]);
  EXPECT_EQ(leftovers["rmse"], clean["rmse"]);
  EXPECT_EQ(leftovers["mean_signed"], clean["mean_signed"]);
  EXPECT_EQ(leftovers["max_error"], clean["max_error"]);
}

// Accumulation blends its passes additively: a blend equation, scissor or
// depth function left behind by a failed job must not reach it.
TEST(Failures, AJobThatFailsMidFrameLeavesNoStateToTheNextJob) {
  Registry registry;
  registry.load_plugins(SHADOWBENCH_PLUGIN_DIR);
  registry.add({"odd_state", "test", "fails with odd GL state", Needs{}, {}, [](const Params&) {
                  return std::make_unique<FailsWithOddState>();
                }});
  const auto run = [&](const nlohmann::json& techniques, const std::string& name) {
    const nlohmann::json config = {
        {"name", name},
        {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 2}}}}}},
        {"techniques", techniques},
        {"resolutions", {{48, 36}}},
        {"frames", {{"warmup", 0}, {"timed", 1}}},
        {"reference", {{"spp", 4}}}};
    return run_with_registry(config, registry, name);
  };
  const nlohmann::json accumulation = {{"name", "accumulation"},
                                       {"params", {{"samples", 8}, {"size", 256}}}};
  const RunOutput alone = run(nlohmann::json::array({accumulation}), "state_alone");
  const RunOutput after = run(nlohmann::json::array({"odd_state", accumulation}), "state_after");
  ASSERT_EQ(after.records.size(), 2u);
  EXPECT_EQ(after.records[0]["status"], "failed");
  ASSERT_EQ(after.records[1]["status"], "ok") << after.records[1].dump();
  EXPECT_EQ(after.records[1]["metrics"]["visibility"]["all"]["rmse"],
            alone.records[0]["metrics"]["visibility"]["all"]["rmse"]);
  EXPECT_EQ(after.records[1]["metrics"]["visibility"]["all"]["mean_signed"],
            alone.records[0]["metrics"]["visibility"]["all"]["mean_signed"]);
}

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
  o.run_dir = process_temp_path("shadowbench_e2e_failures");
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
  EXPECT_EQ(reason.rfind("gl_error: render: gl_error compile frame", 0), 0u) << reason;
  EXPECT_NE(reason.find("GL_INVALID_ENUM"), std::string::npos) << reason;
  EXPECT_EQ(records[2]["status"], "failed");
  EXPECT_EQ(records[2]["reason"], "throws: prepare: cannot prepare");  // the phase named
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
