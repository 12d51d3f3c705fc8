// Alpha masks in every technique (docs/design.md, "Alpha masks everywhere"):
// on foliage, whose leaves are alpha-tested quads, each registered technique
// either honours the masks, and then its error relative to a hard shadow
// map's of the same size is what it is with opaque leaves, or is skipped
// with the planner's reason. One run of every technique on masked foliage
// and on the same trees with opaque leaves, shared by the tests below, so
// that a new plugin is held to the rule without a test of its own.
#include <gtest/gtest.h>

#include <cstdio>
#include <stdexcept>
#include <string>

#include "core/scene_types.h"
#include "e2e_util.h"
#include "plugin/registry.h"

namespace sb::test {

using core::add_scene_type;
using core::AlphaMode;
using core::find_scene_type;
using core::Mesh;
using core::Params;
using core::ParamSpec;
using core::Scene;
using core::SceneType;
using plugin::Registry;
using plugin::TechniqueInfo;

namespace {

using json = nlohmann::json;

// The hard map every technique is held to, at the size every other map gets.
constexpr int kMapSize = 1024;
const std::string kShadowMap = "shadow_map/size=1024";

// Draw no shadow at all (V = 1), so they have no mask to honour: the
// controls of the run, not techniques.
bool is_control(const TechniqueInfo& t) { return t.family == "none" || t.family == "control"; }

// Every technique, with its map size and light samples made small and equal
// where it has them.
json all_techniques(const Registry& registry) {
  json all = json::array();
  for (const TechniqueInfo& t : registry.all()) {
    if (is_control(t)) continue;
    json params = json::object();
    for (const ParamSpec& p : t.params) {
      if (p.name == "size") params["size"] = kMapSize;
      if (p.name == "samples") params["samples"] = 16;  // accumulation, planar_soft
    }
    // Its `shade` options differ in whether they honour masks (two_map_bound).
    if (t.name == "two_map_bound") params["shade"] = json::array({"search", "gradient"});
    all.push_back({{"name", t.name}, {"params", params}});
  }
  return all;
}

// The built plugins, as run_config loads them.
const Registry& plugins() {
  static const Registry r = [] {
    Registry reg;
    reg.load_plugins(SHADOWBENCH_PLUGIN_DIR);
    return reg;
  }();
  return r;
}

// Two trees of foliage at 128×96 (leaf quads with the generated leaf mask,
// a square light of side 1), and the same trees with the masks turned off:
// every leaf quad opaque.
Scene opaque_foliage(const Params& p) {
  Scene s = find_scene_type("foliage")->build(p);
  for (Mesh& m : s.meshes) m.alpha_mode = AlphaMode::Opaque;
  return s;
}

class MaskedCasters : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (find_scene_type("test_opaque_foliage") == nullptr) {
      const SceneType& foliage = *find_scene_type("foliage");
      add_scene_type({"test_opaque_foliage", "foliage with every leaf quad opaque", foliage.params,
                      opaque_foliage});
    }
    const json trees = {{"trees", 2}};
    const json config = {
        {"name", "masked_casters"},
        {"scenes", json::array({{{"type", "foliage"}, {"params", trees}},
                                {{"type", "test_opaque_foliage"}, {"params", trees}}})},
        {"techniques", all_techniques(plugins())},
        {"resolutions", json::array({json::array({128, 96})})},
        {"frames", {{"warmup", 0}, {"timed", 1}}},
        {"reference", {{"spp", 64}}}};
    out_ = new RunOutput(run_config(config, "masked_casters"));
  }
  static void TearDownTestSuite() {
    delete out_;
    out_ = nullptr;
  }
  static const json& record_of(const std::string& scene, const std::string& variant) {
    for (const auto& r : out_->records)
      if (r["scene"]["type"] == scene && r["technique_variant"] == variant) return r;
    throw std::runtime_error("no record of " + scene + " / " + variant);
  }
  static double rmse(const json& record) {
    return record["metrics"]["visibility"]["all"]["rmse"].get<double>();
  }
  // Of the pixels the reference calls lit, the share the job calls umbra:
  // a leaf quad drawn whole shadows the light that passes through its holes.
  static double lit_called_umbra(const json& record) {
    const json& lit = record["classes"]["counts"]["lit"];
    return lit[2].get<double>() /
           (lit[0].get<double>() + lit[1].get<double>() + lit[2].get<double>());
  }
  static RunOutput* out_;
};

RunOutput* MaskedCasters::out_ = nullptr;

// The rule for every technique, future plugins too. A technique's error
// relative to shadow_map's, E(T) / E(shadow_map), is its filter's or its
// soft shadow's doing, and stays about the same whether the leaves are
// masked or opaque if it honours the masks (blurred_visibility's blur makes
// it 2.0 and 2.2). One that ignores them sees opaque quads where the
// reference and shadow_map see holes, and its ratio grows on the masked
// trees. Measured here (2 trees, 128×96): the techniques that honour masks
// grow by 0.84 to 1.08 ×; before this test, extended_light_maps (quads
// drawn whole) grew by 1.88 ×, penumbra_maps by 1.40 ×, smoothies by
// 1.20 × (bands on every quad's outline). The bound, 1.15 ×, lies between.
// two_map_bound's gradient grew by only 1.06 × (its classification is
// masked): the test below holds it to its skip.
TEST_F(MaskedCasters, EveryTechniqueHonoursMasksOrIsSkipped) {
  ASSERT_EQ(out_->summary.failed, 0);
  const double hard_masked = rmse(record_of("foliage", kShadowMap));
  const double hard_opaque = rmse(record_of("test_opaque_foliage", kShadowMap));
  for (const auto& r : out_->records) {
    if (r["scene"]["type"] != "foliage") continue;
    const std::string variant = r["technique_variant"];
    SCOPED_TRACE(variant);
    if (r["status"] == "skipped") {
      EXPECT_FALSE(r.value("reason", "").empty());
      continue;
    }
    ASSERT_EQ(r["status"], "ok");
    const json& opaque = record_of("test_opaque_foliage", variant);
    ASSERT_EQ(opaque["status"], "ok");
    const double masked_ratio = rmse(r) / hard_masked, opaque_ratio = rmse(opaque) / hard_opaque;
    std::printf("%-40s E/E(shadow_map): masked %.3f, opaque %.3f, growth %.3f\n", variant.c_str(),
                masked_ratio, opaque_ratio, masked_ratio / opaque_ratio);
    EXPECT_LE(masked_ratio, 1.15 * opaque_ratio);
  }
}

// The techniques that take their penumbra from the meshes' edges, where a
// mask has no place, are skipped with the planner's reason.
TEST_F(MaskedCasters, EdgeBandTechniquesAreSkippedWithTheReason) {
  for (const char* variant : {"penumbra_maps/size=1024", "smoothies/size=1024",
                              "two_map_bound/shade=gradient,size=1024"}) {
    const json& r = record_of("foliage", variant);
    EXPECT_EQ(r["status"], "skipped") << variant;
    EXPECT_NE(
        r.value("reason", "").find("cannot honour alpha masks: mesh 'leaves' is alpha-tested"),
        std::string::npos)
        << variant << ": " << r.value("reason", "");
  }
  // two_map_bound's search reads only its two maps, which honour the masks.
  EXPECT_EQ(record_of("foliage", "two_map_bound/shade=search,size=1024")["status"], "ok");
}

// extended_light_maps draws its casters through the alpha test: light
// passes through the leaves' holes as it does for shadow_map. Both are hard
// and see the same holes, so of the pixels the reference calls lit they
// may call umbra only a few along the leaves' edges (8-bit depth, another
// bias): at most 0.2 % more than shadow_map (measured: none on either).
// With the quads drawn whole, measured 0.7 % more.
TEST_F(MaskedCasters, ExtendedLightMapsLetLightThroughTheHoles) {
  const json& elm = record_of("foliage", "extended_light_maps/size=1024");
  ASSERT_EQ(elm["status"], "ok");
  const json& hard = record_of("foliage", kShadowMap);
  std::printf("lit pixels called umbra: extended_light_maps %.4f, shadow_map %.4f\n",
              lit_called_umbra(elm), lit_called_umbra(hard));
  EXPECT_LE(lit_called_umbra(elm), lit_called_umbra(hard) + 0.002);
}

}  // namespace
}  // namespace sb::test
