// The plan decides every job before any GL context exists: skips with their
// reasons, failing scenes, and the derived data each scene needs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "../config/cli_runner.h"
#include "config/experiment.h"
#include "gl/context.h"
#include "plan/need_resolution.h"
#include "plan/plan.h"
#include "plugin/registry.h"
#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"
#include "test_registry.h"

namespace sb::test {

using config::Experiment;
using config::load_experiment;
using config::parse_experiment;
using core::AlphaMode;
using core::Mesh;
using core::Scene;
using core::TextureImage;
using plan::Derive;
using plan::make_plan;
using plan::Plan;
using plan::PlannedJob;
using plan::resolve_needs;
using plugin::TechniqueInfo;

namespace {

const std::string kScenesConfig = std::string(SHADOWBENCH_SOURCE_DIR) + "/configs/scenes.json";

const PlannedJob& job(const Experiment& e, const Plan& plan, const std::string& scene,
                      const std::string& technique) {
  for (const auto& j : plan.jobs)
    if (e.scenes[j.scene].name == scene && e.techniques[j.technique].info->name == technique)
      return j;
  throw std::runtime_error("no job " + scene + " / " + technique);
}

TEST(PlanStage, ListsTheFoliageShadowVolumeSkipBeforeAnyGlContext) {
  const Experiment e = load_experiment(kScenesConfig, registry());
  const Plan plan = make_plan(e);
  EXPECT_EQ(gl::contexts_created(), 0u);
  const PlannedJob& skipped = job(e, plan, "foliage", "shadow_volume");
  EXPECT_EQ(skipped.outcome.status, PlannedJob::Status::Skip);
  EXPECT_NE(skipped.outcome.reason.find("needs closed casters: mesh 'leaves'"), std::string::npos)
      << skipped.outcome.reason;
  EXPECT_EQ(job(e, plan, "sphere_grid", "shadow_volume").outcome.status, PlannedJob::Status::Run);
  EXPECT_EQ(plan.jobs.size(), 24u);  // 4 scenes × 6 techniques
  EXPECT_EQ(plan.count(PlannedJob::Status::Skip), 1u);
  // Derived data follow the techniques that will run: adjacency for the
  // sphere grid's shadow volumes, none on foliage, whose volume job is skipped.
  const auto logs = [&](size_t s) {
    std::string all;
    for (const auto& l : plan.scenes[s].log) all += l + "\n";
    return all;
  };
  EXPECT_NE(logs(0).find("edge adjacency"), std::string::npos) << logs(0);
  EXPECT_EQ(logs(2).find("edge adjacency"), std::string::npos) << logs(2);
  EXPECT_NE(logs(2).find("closedness"), std::string::npos) << logs(2);
}

// Every technique that needs closed casters (the shadow-volume family) is
// skipped on an open caster and on an alpha-tested one, with the reason.
TEST(PlanStage, EveryVolumeTechniqueSkipsOpenAndAlphaTestedCastersWithAReason) {
  std::vector<const TechniqueInfo*> volumes;
  for (const TechniqueInfo& t : registry().all())
    if (t.needs.has(plugin::need::kClosedCasters)) volumes.push_back(&t);
  ASSERT_FALSE(volumes.empty());
  const auto scene = [](bool open, bool alpha_tested) {
    Scene s;
    Mesh box = make_box("box", {0, 1, 0}, {0.5f, 1.0f, 1.5f});
    if (open) box.indices.resize(box.indices.size() - 3);
    if (alpha_tested) {
      s.textures.push_back(TextureImage{"holes", 1, 1, {255, 255, 255, 0}});
      box.base_color_texture = 0;
      box.alpha_mode = AlphaMode::Mask;
      box.uvs.assign(box.positions.size(), glm::vec2(0.5f));
    }
    s.meshes.push_back(box);
    s.meshes.push_back(make_ground_plane("ground", glm::vec3(0), 5.0f));
    return s;
  };
  const auto reasons = [&](const Scene& s) {
    return resolve_needs(s, volumes, &registry(), Derive::Decide).skip_reason;
  };
  for (size_t i = 0; i < volumes.size(); ++i) {
    SCOPED_TRACE(volumes[i]->name);
    EXPECT_EQ(reasons(scene(false, false))[i], "");
    EXPECT_NE(reasons(scene(true, false))[i].find("needs closed casters: mesh 'box' has 3 "
                                                  "boundary edges"),
              std::string::npos)
        << reasons(scene(true, false))[i];
    EXPECT_NE(reasons(scene(false, true))[i].find("cannot honour alpha masks: mesh 'box'"),
              std::string::npos)
        << reasons(scene(false, true))[i];
  }
}

// On foliage (alpha-tested leaves) the techniques whose penumbra comes from
// the meshes' edges are skipped with the reason, and only those:
// two_map_bound only with its gradient shade, the one that reads edges.
TEST(PlanStage, EdgeBandTechniquesSkipMaskedCastersWithTheReason) {
  const nlohmann::json config = {
      {"name", "masked"},
      {"scenes", nlohmann::json::array({{{"type", "foliage"}, {"params", {{"trees", 1}}}}})},
      {"techniques",
       nlohmann::json::array(
           {"penumbra_maps",
            "smoothies",
            "extended_light_maps",
            {{"name", "two_map_bound"},
             {"params", {{"shade", nlohmann::json::array({"search", "gradient", "midpoint"})}}}}})},
      {"resolutions", nlohmann::json::array({nlohmann::json::array({32, 24})})}};
  const Experiment e = parse_experiment(config, "masked.json", registry());
  const Plan plan = make_plan(e);
  std::map<std::string, const PlannedJob*> by_variant;
  for (const auto& j : plan.jobs) by_variant[e.techniques[j.technique].name] = &j;
  ASSERT_EQ(by_variant.size(), 6u);
  for (const auto& [variant, j] : by_variant) {
    const bool skipped = variant == "penumbra_maps" || variant == "smoothies" ||
                         variant.find("gradient") != std::string::npos;
    EXPECT_EQ(j->outcome.status, skipped ? PlannedJob::Status::Skip : PlannedJob::Status::Run)
        << variant;
    if (skipped) {
      EXPECT_NE(j->outcome.reason.find("cannot honour alpha masks: mesh 'leaves' is alpha-tested"),
                std::string::npos)
          << variant << ": " << j->outcome.reason;
    }
  }
}

TEST(PlanStage, ABadSceneFailsItsJobsAndTheRestArePlanned) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "shadowbench_test_plan_bad_scene";
  std::filesystem::create_directories(dir);
  const std::string config = (dir / "bad.json").string();
  std::ofstream(config) << R"({"name":"bad","scenes":[{"type":"sphere_grid","params":{"grid":2}},)"
                        << R"({"type":"gltf","params":{"file":"missing.glb"}}],)"
                        << R"("techniques":["none","shadow_volume"],"resolutions":[[32,24]]})";
  const Experiment e = load_experiment(config, registry());
  const Plan plan = make_plan(e);
  EXPECT_EQ(plan.count(PlannedJob::Status::Run), 2u);
  EXPECT_EQ(plan.count(PlannedJob::Status::Fail), 2u);
  EXPECT_TRUE(plan.scenes[1].bad_input);
  EXPECT_NE(plan.scenes[1].input_error.find("missing.glb"), std::string::npos);
  // The plan command prints what it can, then says "bad input" with exit 2.
  const auto r = run_cli("plan " + config);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("run  32x24  shadow_volume"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("missing.glb"), std::string::npos) << r.output;
  // `plan --json` writes the whole plan too, the bad scene's jobs failing as bad input.
  const auto as_json = run_cli("plan " + config + " --json", false);
  EXPECT_EQ(as_json.exit_code, 2);
  const nlohmann::json j = nlohmann::json::parse(as_json.output, nullptr, false);
  ASSERT_EQ(j["jobs"].size(), 4u) << as_json.output;
  EXPECT_EQ(j["scenes"][1]["bad_input"], true);
  EXPECT_NE(j["scenes"][1]["input_error"].get<std::string>().find("missing.glb"),
            std::string::npos);
  for (size_t i = 0; i < 4; ++i) {
    const bool bad = i >= 2;
    EXPECT_EQ(j["jobs"][i]["outcome"], bad ? "fail" : "run") << i;
    EXPECT_EQ(j["jobs"][i]["bad_input"], bad) << i;
  }
}

TEST(PlanStage, ValidateAndPlanCountTheSkips) {
  const auto v = run_cli("validate " + kScenesConfig);
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_NE(v.output.find("24 jobs (23 to run, 1 skipped"), std::string::npos) << v.output;
  const auto p = run_cli("plan " + kScenesConfig);
  EXPECT_EQ(p.exit_code, 0) << p.output;
  EXPECT_NE(p.output.find("skip 800x600  shadow_volume/mode=zfail  (shadow_volume needs closed "
                          "casters: mesh 'leaves'"),
            std::string::npos)
      << p.output;
}

}  // namespace
}  // namespace sb::test
