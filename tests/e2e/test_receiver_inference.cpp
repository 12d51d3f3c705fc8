// Receivers in ordinary glTF files (scenes/receiver_inference.h): an open
// ground quad under closed objects casts in the file, yet can shadow
// nothing, so it is inferred a receiver; volume techniques then run on it and
// agree with shadow maps. A plane with something under it stays a caster.
#include <gtest/gtest.h>

#include <cmath>

#include "../gltf/gltf_builder.h"
#include "core/scene.h"
#include "e2e_util.h"
#include "scenes/receiver_inference.h"

namespace sb::test {

using core::ImageF;
using core::Mesh;
using core::Scene;

namespace {

void add_mesh(GltfBuilder& b, const std::string& name, const std::vector<float>& xyz,
              const std::vector<uint16_t>& indices) {
  const int pos = b.positions(xyz);
  const int idx = b.accessor(indices, 5123, "SCALAR", indices.size());
  b.node(
      {{"name", name}, {"mesh", b.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}});
}

// A 20×20 ground quad (open, casting as every exported ground does) and a
// closed unit cube standing on it; optionally an open roof quad over the cube.
std::string write_ground_scene(const TempDir& dir, bool roof) {
  GltfBuilder b;
  add_mesh(b, "ground", {-10, 0, -10, -10, 0, 10, 10, 0, 10, 10, 0, -10}, {0, 1, 2, 0, 2, 3});
  std::vector<float> cube;
  for (int i = 0; i < 8; ++i) {
    cube.push_back((i & 1) ? 0.5f : -0.5f);
    cube.push_back((i & 2) ? 1.0f : 0.0f);
    cube.push_back((i & 4) ? 0.5f : -0.5f);
  }
  add_mesh(b, "cube", cube, {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4,
                             2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6});
  if (roof)
    add_mesh(b, "roof", {-1, 2.5f, -1, -1, 2.5f, 1, 1, 2.5f, 1, 1, 2.5f, -1}, {0, 1, 2, 0, 2, 3});
  return b.save_gltf(dir / (roof ? "roofed.gltf" : "ground.gltf"));
}

json experiment(const std::string& file, bool infer) {
  json scene = {{"type", "gltf"},
                {"params", {{"file", file}}},
                {"light", {{"center", {4.0, 3.0, 1.5}}, {"target", {0, 0, 0}}, {"size", 0.5}}},
                {"camera", {{"eye", {-1.0, 3.0, 4.0}}, {"target", {-1.0, 0.0, 0.0}}}}};
  if (!infer) scene["infer_receivers"] = false;
  return {{"name", "receivers"},
          {"scenes", json::array({scene})},
          {"techniques", json::array({json{{"name", "shadow_map"}, {"params", {{"size", 1024}}}},
                                      "shadow_volume"})},
          {"resolutions", json::array({json::array({96, 72})})},
          {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"spp", 16}, {"cache", false}}}};
}

TEST(ReceiverInference, AnOpenGroundUnderClosedObjectsIsAReceiverAndVolumesRunOnIt) {
  TempDir dir;
  const auto out = run_config(experiment(write_ground_scene(dir, false), true), "receivers_on");
  ASSERT_EQ(out.records.size(), 2u);
  const json& volume = out.record("shadow_volume");
  ASSERT_EQ(volume["status"], "ok") << volume.value("reason", "");
  EXPECT_EQ(volume["scene"]["derived"]["inferred_receivers"], json::array({"ground"}));
  EXPECT_EQ(volume["scene"]["caster_triangles"], 12);
  // Both are hard shadows from the light's centre: they differ at most on
  // the shadow's outline.
  const ImageF a = out.visibility("shadow_volume");
  const ImageF b = out.visibility("shadow_map/size=1024");
  size_t differ = 0, shadowed = 0;
  for (size_t i = 0; i < a.data.size(); ++i) {
    differ += std::fabs(a.data[i] - b.data[i]) > 0.5f ? 1 : 0;
    shadowed += a.data[i] < 0.5f ? 1 : 0;
  }
  EXPECT_GT(shadowed, 200u) << "the cube's shadow must be in view";
  EXPECT_LT(double(differ), 0.02 * double(a.data.size()));
}

TEST(ReceiverInference, TurnedOffTheGroundCastsAndVolumesAreSkipped) {
  TempDir dir;
  const auto out = run_config(experiment(write_ground_scene(dir, false), false), "receivers_off");
  const json& volume = out.record("shadow_volume");
  EXPECT_EQ(volume["status"], "skipped");
  EXPECT_NE(volume["reason"].get<std::string>().find("mesh 'ground'"), std::string::npos);
  EXPECT_EQ(volume["scene"]["derived"]["receiver_inference"], false);
  EXPECT_TRUE(volume["scene"]["derived"]["inferred_receivers"].empty());
}

TEST(ReceiverInference, APlaneWithAnythingUnderItStaysACaster) {
  TempDir dir;
  const auto out = run_config(experiment(write_ground_scene(dir, true), true), "receivers_roof");
  const json& record = out.record("shadow_map/size=1024");
  ASSERT_EQ(record["status"], "ok") << record.value("reason", "");
  EXPECT_EQ(record["scene"]["derived"]["inferred_receivers"], json::array({"ground"}));
  EXPECT_EQ(record["scene"]["caster_triangles"], 14) << "cube and roof";
}

// A file with nothing but its ground: once inferred a receiver, the scene has
// no caster at all, and every technique must say "all lit", as the
// reference does, rather than fail.
TEST(ReceiverInference, AGroundAloneLeavesNoCasterAndEveryTechniqueSaysLit) {
  TempDir dir;
  GltfBuilder b;
  add_mesh(b, "ground", {-10, 0, -10, -10, 0, 10, 10, 0, 10, 10, 0, -10}, {0, 1, 2, 0, 2, 3});
  json config = experiment(b.save_gltf(dir / "ground_only.gltf"), true);
  config["techniques"] = json::array({"shadow_map", "vsm", "shadow_volume", "accumulation"});
  const auto out = run_config(config, "receivers_ground_only");
  ASSERT_EQ(out.records.size(), 4u);
  for (const json& r : out.records) {
    ASSERT_EQ(r["status"], "ok") << r["technique_variant"] << ": " << r.value("reason", "");
    EXPECT_EQ(r["scene"]["caster_triangles"], 0);
    EXPECT_EQ(r["metrics"]["visibility"]["all"]["max_error"].get<double>(), 0.0)
        << r["technique_variant"];
  }
}

// The rule on its own: the light must lie strictly on one side, and every
// other mesh on that side or on the plane.
TEST(ReceiverInference, NeedsTheWholeLightAndEveryOtherMeshOnOneSide) {
  const auto quad = [](const std::string& name, float y) {
    Mesh m;
    m.name = name;
    m.positions = {{-1, y, -1}, {-1, y, 1}, {1, y, 1}, {1, y, -1}};
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
  };
  Scene s;
  s.meshes = {quad("low", 0.0f), quad("tile", 0.0f), quad("high", 1.0f)};
  s.light.center = {0, 5, 0};
  Scene light_between = s;
  EXPECT_EQ(infer_receivers(s), (std::vector<std::string>{"low", "tile"}));
  EXPECT_FALSE(s.meshes[0].casts_shadow);
  EXPECT_TRUE(s.meshes[2].casts_shadow);
  // With the light between the planes, "high" has the light below it and
  // the other quads too: a receiver when the camera is below it as well;
  // "low" and "tile" have "high" on the light's side: receivers too.
  light_between.light.center = {0, 0.5f, 0};
  light_between.camera.eye = {0, 0.5f, 10};
  Scene camera_above = light_between;
  EXPECT_EQ(infer_receivers(light_between), (std::vector<std::string>{"low", "tile", "high"}));
  // Seen from above, "high" shows the camera its other side.
  camera_above.camera.eye = {0, 5, 10};
  EXPECT_EQ(infer_receivers(camera_above), (std::vector<std::string>{"low", "tile"}));
  // Geometry sunk into a ground by up to a thousandth of the scene's radius
  // (here 1.41) is hidden by it; deeper, it is not. (The sunk quad itself
  // has everything above it.)
  Scene sunk = s;
  for (auto& m : sunk.meshes) m.casts_shadow = true;
  sunk.meshes[2] = quad("roots", -0.001f);
  EXPECT_EQ(infer_receivers(sunk), (std::vector<std::string>{"low", "tile", "roots"}));
  sunk.meshes[2] = quad("roots", -0.01f);
  for (auto& m : sunk.meshes) m.casts_shadow = true;
  EXPECT_EQ(infer_receivers(sunk), (std::vector<std::string>{"roots"}));
  // A light rectangle cut by the plane: not inferred.
  Scene tilted;
  tilted.meshes = {quad("low", 0.0f)};
  tilted.light.center = {0, 0.2f, 0};
  tilted.light.half_u = {0, 0.5f, 0};
  EXPECT_TRUE(infer_receivers(tilted).empty());
}

}  // namespace
}  // namespace sb::test
