// A run's plan keeps its scenes' builds for the run within a memory budget
// (make_plan's keep_bytes), and the run completes a kept build with the Run
// needs' data, as a build for the run would have made it, without building
// the scene or deriving anything twice (issue 65).
#include <gtest/gtest.h>

#include <string>

#include "config/experiment.h"
#include "plan/plan.h"
#include "scenes/need_providers.h"
#include "test_registry.h"

namespace sb::test {

using json = nlohmann::json;
using config::Experiment;
using config::parse_experiment;
using core::Mesh;
using core::Scene;
using plan::Derive;
using plan::derive_run_needs;
using plan::make_plan;
using plan::Plan;
using plan::plan_scene;
using plan::scene_bytes;
using plan::ScenePlan;

namespace {

Experiment experiment(const json& scenes, const json& techniques) {
  const json config = {{"name", "kept"},
                       {"scenes", scenes},
                       {"techniques", techniques},
                       {"resolutions", json::array({"32x24"})}};
  return parse_experiment(config, "kept.json", registry());
}

json grid(const std::string& label, int n) {
  return {{"type", "sphere_grid"}, {"label", label}, {"params", {{"grid", n}}}};
}

TEST(KeptScenes, SceneBytesCountVerticesIndicesAndTexels) {
  Scene s;
  Mesh m;
  m.positions.assign(3, glm::vec3(0));
  m.normals.assign(3, glm::vec3(0, 1, 0));
  m.uvs.assign(3, glm::vec2(0));
  m.indices = {0, 1, 2};
  s.meshes.push_back(m);
  s.textures.push_back({"t", 2, 2, std::vector<uint8_t>(16, 255)});
  // 3 × (12 + 12 + 8) vertex bytes, 3 × 4 index bytes, 2 × 2 × 4 texel bytes.
  EXPECT_EQ(scene_bytes(s), 96u + 12u + 16u);
}

TEST(KeptScenes, APlanKeepsScenesInPlanOrderWhileTheyFitTheBudget) {
  const Experiment e =
      experiment(json::array({grid("small", 2), grid("large", 3)}), json::array({"shadow_map"}));
  const size_t small = scene_bytes(config::build_scene(e.scenes[0], e.file));
  const size_t large = scene_bytes(config::build_scene(e.scenes[1], e.file));
  ASSERT_LT(small, large);
  const auto kept = [&](size_t budget) {
    const Plan p = make_plan(e, 1, budget);
    std::string out;
    for (const ScenePlan& s : p.scenes) {
      // A scene not kept holds no meshes; a kept one all of its build.
      EXPECT_EQ(s.kept, !s.scene.meshes.empty());
      out += s.kept ? "k" : "-";
    }
    return out;
  };
  EXPECT_EQ(kept(0), "--");  // plan and validate keep nothing
  EXPECT_EQ(kept(small - 1), "--");
  EXPECT_EQ(kept(small), "k-");
  EXPECT_EQ(kept(small + large - 1), "k-");
  EXPECT_EQ(kept(small + large), "kk");
  // The only scene is kept whatever its size: the run would build it at once.
  const Experiment one = experiment(json::array({grid("large", 3)}), json::array({"shadow_map"}));
  EXPECT_TRUE(make_plan(one, 1, 1).scenes[0].kept);
  EXPECT_FALSE(make_plan(one, 1, 0).scenes[0].kept);
}

// shadow_map asks for closedness (a Plan need), shadow_volume for edge
// adjacency (a Run need, derived only to run).
TEST(KeptScenes, DerivingTheRunNeedsOfAKeptPlanMakesWhatARunsBuildMakesAndNothingTwice) {
  const Experiment e =
      experiment(json::array({grid("grid", 2)}), json::array({"shadow_map", "shadow_volume"}));
  const ScenePlan full = plan_scene(e, e.scenes[0], Derive::All);
  ASSERT_TRUE(full.error.empty()) << full.error;
  size_t casters = 0;
  for (const Mesh& m : full.scene.meshes) casters += m.casts_shadow ? 1 : 0;
  ASSERT_GT(casters, 0u);

  const DerivedDataCounters before = derived_data_counters();
  Plan p = make_plan(e, 1, plan::kRunKeptSceneBytes);
  ScenePlan& kept = p.scenes[0];
  ASSERT_TRUE(kept.kept);
  EXPECT_EQ(kept.derived_for, Derive::Decide);
  EXPECT_EQ(derived_data_counters().closedness_checks, before.closedness_checks + casters);
  EXPECT_EQ(derived_data_counters().adjacency_builds, before.adjacency_builds);
  const size_t searches = derived_data_counters().receiver_searches;

  derive_run_needs(e, kept);
  EXPECT_EQ(kept.derived_for, Derive::All);
  // The Plan needs are not derived again; the Run need once, for each caster.
  EXPECT_EQ(derived_data_counters().closedness_checks, before.closedness_checks + casters);
  EXPECT_EQ(derived_data_counters().receiver_searches, searches);
  EXPECT_EQ(derived_data_counters().adjacency_builds, before.adjacency_builds + casters);
  derive_run_needs(e, kept);  // derived already: nothing more
  EXPECT_EQ(derived_data_counters().adjacency_builds, before.adjacency_builds + casters);

  EXPECT_EQ(kept.log, full.log);
  EXPECT_EQ(kept.derived.names(), full.derived.names());
  EXPECT_EQ(kept.skip_reason, full.skip_reason);
  EXPECT_EQ(kept.needs, full.needs);
  EXPECT_EQ(kept.uploads, full.uploads);
  EXPECT_EQ(kept.inferred_receivers, full.inferred_receivers);
  EXPECT_EQ(kept.scene.triangle_count(), full.scene.triangle_count());
  for (size_t t = 0; t < e.techniques.size(); ++t)
    EXPECT_EQ(plan::decide_job(e, kept, t), plan::decide_job(e, full, t)) << t;
}

}  // namespace
}  // namespace sb::test
