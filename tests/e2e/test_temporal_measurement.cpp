// A temporal technique (TechniqueInfo::temporal: its frames depend on the
// frames before them) has its V measured on frame `frames.history` of a
// fresh prepare(), so its error does not depend on how many frames the
// timing took; the record says which frame (technique.measured_frame).
#include <gtest/gtest.h>

#include <memory>

#include "e2e_util.h"
#include "gl/gl.h"
#include "plugin/registry.h"

namespace sb::test {

using core::Params;
using plugin::FrameInputs;
using plugin::Needs;
using plugin::Registry;
using plugin::Technique;

namespace {

// V = 1 / (frames rendered since prepare()) everywhere.
class OneOverFrame final : public Technique {
 public:
  void prepare(const FrameInputs& /*in*/) override { frame_ = 0; }
  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    auto pass = timer.scope("count");
    const float v[4] = {1.0f / float(++frame_), 0, 0, 0};
    glClearNamedFramebufferfv(in.visibility_framebuffer, GL_COLOR, 0, v);
  }

 private:
  int frame_ = 0;
};

nlohmann::json config(int timed, int history) {
  return {{"name", "temporal"},
          {"scenes", {{{"type", "sphere_grid"}, {"params", {{"grid", 2}}}}}},
          {"techniques", {"one_over_frame"}},
          {"resolutions", {{32, 24}}},
          {"frames", {{"warmup", 1}, {"timed", timed}, {"history", history}}},
          {"reference", {{"spp", 4}}}};
}

// The mean of V - reference over the measured pixels, and the record.
struct Measured {
  double mean_signed;
  nlohmann::json technique;
};

Measured measure(bool temporal, int timed, int history, const std::string& name) {
  Registry registry;
  plugin::TechniqueInfo info{
      "one_over_frame", "test", "V = 1 / frame",
      Needs{},          {},     [](const Params&) { return std::make_unique<OneOverFrame>(); }};
  info.temporal = temporal;
  registry.add(std::move(info));
  const RunOutput out = run_with_registry(config(timed, history), registry, name);
  EXPECT_EQ(out.summary.ok, 1);
  const nlohmann::json& r = out.records.at(0);
  return {r["metrics"]["visibility"]["all"]["mean_signed"].get<double>(), r["technique"]};
}

TEST(TemporalMeasurement, ATemporalTechniquesVComesFromFrameHistoryWhateverTheTimedFrames) {
  const Measured three = measure(true, 3, 5, "temporal_3");
  const Measured seven = measure(true, 7, 5, "temporal_7");
  EXPECT_EQ(three.mean_signed, seven.mean_signed);
  EXPECT_EQ(three.technique["measured_frame"], 5);
  // Frame 5's V is 1/5, frame 9's 1/9: the history decides the figure (on
  // every measured pixel but the few in attached shadow, where both V are 0).
  const Measured nine = measure(true, 3, 9, "temporal_h9");
  EXPECT_NEAR(three.mean_signed - nine.mean_signed, 1.0 / 5.0 - 1.0 / 9.0, 0.002);
}

// Without the flag the last frame of the schedule is measured: how many
// frames the timing took shows in the error, which is what the flag is for.
TEST(TemporalMeasurement, WithoutTheFlagTheTimedFrameCountShowsInTheError) {
  const Measured three = measure(false, 3, 5, "plain_3");
  const Measured seven = measure(false, 7, 5, "plain_7");
  EXPECT_NE(three.mean_signed, seven.mean_signed);
  EXPECT_FALSE(three.technique.contains("measured_frame"));
}

}  // namespace
}  // namespace sb::test
