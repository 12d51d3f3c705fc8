// What goes into a depth map, and what a lookup may trust: only receivers
// with nothing behind them join filtered maps; open casters are never culled;
// points behind the light's eye plane are not mirrored into the map.
#include <gtest/gtest.h>

#include <cmath>

#include "../gltf/gltf_builder.h"
#include "e2e_util.h"

namespace sb::test {
namespace {

void add_mesh(GltfBuilder& b, const std::string& name, const std::vector<float>& xyz,
              const std::vector<uint16_t>& indices, bool casts = true) {
  const int pos = b.positions(xyz);
  const int idx = b.accessor(indices, 5123, "SCALAR", indices.size());
  json node = {{"name", name},
               {"mesh", b.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", idx}})}};
  if (!casts) node["extras"] = {{"shadowbench_mesh", {{"casts_shadow", false}}}};
  b.node(node);
}

// A quad at height y over [x0,x1]×[z0,z1], facing up (counter-clockwise
// seen from above).
std::vector<float> quad(float x0, float x1, float z0, float z1, float y) {
  return {x0, y, z0, x0, y, z1, x1, y, z1, x1, y, z0};
}
const std::vector<uint16_t> kQuad = {0, 1, 2, 0, 2, 3};

void add_cube(GltfBuilder& b, const glm::vec3& lo, const glm::vec3& hi) {
  std::vector<float> p;
  for (int i = 0; i < 8; ++i) {
    p.push_back((i & 1) ? hi.x : lo.x);
    p.push_back((i & 2) ? hi.y : lo.y);
    p.push_back((i & 4) ? hi.z : lo.z);
  }
  add_mesh(b, "cube", p, {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4,
                          2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6});
}

json experiment(const std::string& file, const json& light, const json& camera,
                const json& techniques) {
  return {{"name", "maps"},
          {"scenes", json::array({{{"type", "gltf"},
                                   {"params", {{"file", file}}},
                                   {"light", light},
                                   {"camera", camera}}})},
          {"techniques", techniques},
          {"resolutions", json::array({json::array({96, 72})})},
          {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"spp", 64}, {"cache", false}}}};
}

double rmse(const json& record) {
  EXPECT_EQ(record["status"], "ok") << record.value("reason", "");
  return record["metrics"]["visibility"]["all"]["rmse"].get<double>();
}

// A non-casting canopy (the file says so) around a pillar, within the
// casters' depth range from the light: the reference sees the ground lit
// through it. Drawn into a filtered map, it would shadow everything under it.
TEST(MapContents, AReceiverAboveACasterStaysOutOfFilteredMaps) {
  TempDir dir;
  GltfBuilder b;
  add_mesh(b, "ground", quad(-10, 10, -10, 10, 0), kQuad);
  add_cube(b, {-0.3f, 0.0f, -0.3f}, {0.3f, 3.0f, 0.3f});
  add_mesh(b, "canopy", quad(-2, 2, -2, 2, 2.0f), kQuad, /*casts=*/false);
  const auto file = b.save_gltf(dir / "canopy.gltf");
  const json techniques = json::array({json{{"name", "vsm"}, {"params", {{"size", 512}}}},
                                       json{{"name", "esm"}, {"params", {{"size", 512}}}},
                                       json{{"name", "msm"}, {"params", {{"size", 512}}}}});
  const auto out = run_config(
      experiment(file, {{"center", {1.0, 6.0, 0.5}}, {"target", {0, 0, 0}}, {"size", 0.5}},
                 {{"eye", {0.0, 1.2, 5.0}}, {"target", {0.0, 0.3, 0.0}}}, techniques),
      "maps_canopy");
  ASSERT_EQ(out.records.size(), 3u);
  for (const char* t : {"vsm/size=512", "esm/size=512", "msm/size=512"})
    EXPECT_LT(rmse(out.record(t)), 0.08) << t;
}

// An open, single-sided roof quad facing the light: culling front faces
// (every map technique's default) would drop the only face it has.
TEST(MapContents, AnOpenSingleSidedCasterIsNeverCulled) {
  TempDir dir;
  GltfBuilder b;
  add_mesh(b, "ground", quad(-10, 10, -10, 10, 0), kQuad);
  add_mesh(b, "roof", quad(-1, 1, -1, 1, 1.5f), kQuad);
  const auto file = b.save_gltf(dir / "roof.gltf");
  const json techniques =
      json::array({json{{"name", "shadow_map"}, {"params", {{"size", 512}, {"cull", "front"}}}},
                   json{{"name", "shadow_map"}, {"params", {{"size", 512}, {"cull", "back"}}}},
                   json{{"name", "pcss"}, {"params", {{"size", 512}}}},
                   json{{"name", "csm_convolution"}, {"params", {{"size", 512}}}}});
  const auto out = run_config(
      experiment(file, {{"center", {0.3, 6.0, 0.2}}, {"target", {0, 0, 0}}, {"size", 0.5}},
                 {{"eye", {0.0, 4.0, 4.0}}, {"target", {0.0, 0.0, 0.0}}}, techniques),
      "maps_roof");
  ASSERT_EQ(out.records.size(), 4u);
  // The roof's shadow is in view, and every technique draws it.
  size_t shadowed = 0;
  for (float v : out.reference_visibility().data) shadowed += v < 0.5f ? 1 : 0;
  ASSERT_GT(shadowed, 300u);
  for (const json& r : out.records) EXPECT_LT(rmse(r), 0.15) << r["technique_variant"];
}

// A light looking sideways at a cube above its own height: ground behind
// the light's eye plane projects, mirrored through the eye, onto the cube's
// image in the map; nothing stands between that ground and the light.
TEST(MapContents, PointsBehindTheLightAreNotMirroredIntoTheMap) {
  TempDir dir;
  GltfBuilder b;
  add_mesh(b, "ground", quad(-10, 10, -10, 10, 0), kQuad);
  add_cube(b, {-3.5f, 1.4f, -0.5f}, {-2.5f, 2.4f, 0.5f});
  const auto file = b.save_gltf(dir / "behind.gltf");
  const json techniques =
      json::array({json{{"name", "shadow_map"}, {"params", {{"size", 512}}}},
                   json{{"name", "pcf_box"}, {"params", {{"size", 512}}}},
                   json{{"name", "vsm"}, {"params", {{"size", 512}}}},
                   json{{"name", "accumulation"}, {"params", {{"size", 256}, {"samples", 4}}}}});
  const auto out = run_config(
      experiment(file, {{"center", {0.0, 1.0, 0.0}}, {"target", {-5.0, 1.0, 0.0}}, {"size", 0.4}},
                 {{"eye", {2.5, 3.0, 3.0}}, {"target", {2.5, 0.0, 0.0}}}, techniques),
      "maps_behind");
  ASSERT_EQ(out.records.size(), 4u);
  for (const json& r : out.records) {
    EXPECT_LT(rmse(r), 0.02) << r["technique_variant"];
    EXPECT_EQ(r["metrics"]["visibility"]["all"]["frac_over_0.1"].get<double>(), 0.0)
        << r["technique_variant"];
  }
}

}  // namespace
}  // namespace sb::test
