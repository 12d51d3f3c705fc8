// Every technique runs through configs/stress.json, shrunk (32×24, one
// frame, two flicker frames, no sensitivity, a 4-spp reference), without
// crashing the harness: the broken cases (linear-space ESM at c = 200) are
// failed records with their NaN counts, the cases no technique of a kind can
// cover fail with the reason docs/stability.md gives, closed-caster
// techniques skip zero-area triangles, the linear-light technique every
// light but a segment and the rectangle techniques a segment, and every
// other job is ok; the
// jeep's error is the same at scales 1e-3, 1 and 1e4.
// The config's 24 scenes run in six groups, one test each (a ctest shard
// each, about a sixth of the two minutes all of them take); every scene is
// in exactly one group (TheGroupsHoldEverySceneOnce).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "../e2e/e2e_util.h"

namespace sb {
namespace {

using json = nlohmann::json;

json stress_config() {
  std::ifstream in(SHADOWBENCH_SOURCE_DIR "/configs/stress.json");
  return json::parse(in);
}

// The scenes by label, in groups of about equal cost; the jeep's three
// scales together, for their comparison.
struct Group {
  const char* name;
  std::vector<std::string> labels;
};
const Group kGroups[] = {
    {"JeepAtThreeScales", {"jeep_scale_1e-3", "jeep_scale_1", "jeep_scale_1e4"}},
    {"TinyAndHugeLights",
     {"light_1e-4", "light_10x_scene", "linear_light_1e-4", "linear_light_10x_scene"}},
    {"GrazingLightAndViews",
     {"grazing_85deg", "grazing_89deg", "view_along_light", "near_1e-4_far_1e5"}},
    {"PlatesNearReceiverAndLight",
     {"touching_receiver", "nearly_touching_light", "linear_light_across_edge",
      "linear_light_along_edge"}},
    {"BadTriangles",
     {"sliver_triangles", "degenerate_triangles", "coincident_surfaces", "one_texel_rods"}},
    {"CameraAndLightPlacement",
     {"camera_in_shadow_volume", "standing_on_receiver", "light_larger_than_caster",
      "light_behind_camera", "light_facing_camera"}},
};

TEST(StressConfig, TheGroupsHoldEverySceneOnce) {
  std::multiset<std::string> grouped;
  for (const Group& g : kGroups) grouped.insert(g.labels.begin(), g.labels.end());
  std::multiset<std::string> labels;
  const json config = stress_config();
  for (const json& scene : config["scenes"]) labels.insert(scene["label"].get<std::string>());
  EXPECT_EQ(grouped, labels);
}

// gtest prints a parameter that fails: its name is enough.
void PrintTo(const Group& g, std::ostream* os) { *os << g.name; }

class StressGroup : public ::testing::TestWithParam<Group> {};

TEST_P(StressGroup, EveryTechniqueRunsThroughTheStressCasesAndOnlyTheDocumentedOnesFail) {
  const Group& group = GetParam();
  json config = stress_config();
  config["resolutions"] = {{32, 24}};
  config["frames"] = {{"warmup", 0}, {"timed", 1}, {"control", nullptr}};
  config["reference"] = {{"spp", 4}};
  config["stability"] = {{"flicker_frames", 2}, {"sensitivity", false}};
  json scenes = json::array();
  for (json& scene : config["scenes"]) {
    const std::string label = scene["label"].get<std::string>();
    if (std::find(group.labels.begin(), group.labels.end(), label) == group.labels.end()) continue;
    if (scene["type"] == "gltf")
      scene["params"]["file"] =
          SHADOWBENCH_SOURCE_DIR "/configs/" + scene["params"]["file"].get<std::string>();
    scenes.push_back(scene);
  }
  ASSERT_EQ(scenes.size(), group.labels.size());
  config["scenes"] = scenes;
  const bool has_linear_light =
      std::any_of(group.labels.begin(), group.labels.end(),
                  [](const std::string& l) { return l.rfind("linear_light_", 0) == 0; });
  const test::RunOutput out =
      test::run_config(config, std::string("stability_stress_") + group.name);
  ASSERT_EQ(out.records.size(), config["scenes"].size() * 40u);
  std::map<std::string, int> ok;
  // RMSE of V by technique variant and scale, for the jeep at 1e-3, 1, 1e4.
  std::map<std::string, std::map<std::string, double>> by_scale;
  for (const json& r : out.records) {
    const std::string technique = r["technique"]["name"].get<std::string>();
    const std::string scene = r["scene_variant"].get<std::string>();
    SCOPED_TRACE(scene + " " + r["technique_variant"].get<std::string>());
    if (r["status"] == "ok") {
      ++ok[technique];
      if (scene.rfind("jeep_scale_", 0) == 0)
        by_scale[r["technique_variant"].get<std::string>()][scene.substr(0, scene.find('/'))] =
            r["metrics"]["visibility"]["all"]["rmse"].get<double>();
      EXPECT_TRUE(r["stability"].contains("flicker"));
      continue;
    }
    const std::string reason = r.value("reason", "");
    if (r["status"] == "skipped") {
      // Closed-caster techniques on zero-area triangles; the linear-light
      // technique on every other light, and the techniques that need a
      // rectangle on the segments (docs/linear_lights.md).
      const bool linear_light = scene.rfind("linear_light_", 0) == 0;
      if (technique == "heidrich_linear") {
        EXPECT_FALSE(linear_light) << reason;
        EXPECT_NE(reason.find("needs a linear light"), std::string::npos) << reason;
      } else if (linear_light) {
        EXPECT_NE(reason.find("needs a rectangular light"), std::string::npos) << reason;
      } else {
        EXPECT_EQ(scene.rfind("degenerate_triangles", 0), 0u) << reason;
      }
      continue;
    }
    // Linear-space ESM at c = 200 overflows: broken, with its NaN count.
    const bool linear_esm =
        r["technique_variant"].get<std::string>().find("log_space=false") != std::string::npos;
    // One perspective map, or slices in front of the light, cannot cover a
    // plate 0.01 under the light.
    const bool under_light = scene.rfind("nearly_touching_light", 0) == 0;
    EXPECT_TRUE(linear_esm || under_light) << reason;
    if (linear_esm && !under_light) {
      ASSERT_TRUE(r.contains("visibility_check")) << reason;
      EXPECT_GT(r["visibility_check"]["nonfinite"].get<std::int64_t>(), 0) << reason;
    }
    // The maps from the light say the caster reaches its plane; PSM, whose
    // map is not from the light itself, that the scene surrounds the
    // light's post-perspective image.
    if (under_light && !linear_esm) {
      EXPECT_NE(reason.find(technique == "psm" ? "post-perspective" : "reaches the light's plane"),
                std::string::npos)
          << reason;
    }
  }
  // Every technique the config names has jobs that ran in this group
  std::set<std::string> techniques;
  for (const json& t : config["techniques"])
    techniques.insert(t.is_string() ? t.get<std::string>() : t["name"].get<std::string>());
  // (the linear-light technique where the group has a linear light).
  for (const std::string& t : techniques)
    if (t != "heidrich_linear" || has_linear_light) {
      EXPECT_GT(ok[t], 0) << t;
    }
  // The scene's scale changes no technique's error beyond its own noise
  // (the group of the jeep's scales).
  if (std::string(group.name) != "JeepAtThreeScales") {
    EXPECT_TRUE(by_scale.empty());
    return;
  }
  // At 32×24 one pixel that changes by ½ moves the RMSE by up to 0.018:
  // measured at most 0.0034 apart, except penumbra_maps, 0.0106 at 1e4 (one
  // pixel; at 128×96 its three scales agree within 1e-4).
  for (const auto& [variant, rmse] : by_scale) {
    ASSERT_EQ(rmse.size(), 3u) << variant;
    EXPECT_NEAR(rmse.at("jeep_scale_1e-3"), rmse.at("jeep_scale_1"), 0.018) << variant;
    EXPECT_NEAR(rmse.at("jeep_scale_1e4"), rmse.at("jeep_scale_1"), 0.018) << variant;
  }
  EXPECT_GE(by_scale.size(), 38u);
}

INSTANTIATE_TEST_SUITE_P(Stress, StressGroup, ::testing::ValuesIn(kGroups),
                         [](const ::testing::TestParamInfo<Group>& p) { return p.param.name; });

}  // namespace
}  // namespace sb
