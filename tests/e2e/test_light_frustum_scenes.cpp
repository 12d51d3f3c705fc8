// Scenes every shadow-map technique used to fail with "the light lies inside
// the casters' bounding sphere": an ordinary glTF file whose ground casts,
// and a 12×12 sphere grid. Every technique must now give an ok record
// (shadow_volume too: the glTF's open ground is inferred a receiver).
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../gltf/gltf_builder.h"
#include "e2e_util.h"

namespace sb::test {
namespace {

// A 20×20 ground quad and a closed unit cube standing on it, no extras: the
// ground casts, as in every glTF a user exports from a DCC tool.
std::string write_ground_and_cube(const std::filesystem::path& dir) {
  std::vector<float> p = {-10, 0, -10, -10, 0, 10, 10, 0, 10, 10, 0, -10};
  std::vector<uint16_t> idx = {0, 1, 2, 0, 2, 3};
  const uint16_t base = 4;
  for (int i = 0; i < 8; ++i) {
    p.push_back((i & 1) ? 0.5f : -0.5f);
    p.push_back((i & 2) ? 1.0f : 0.0f);
    p.push_back((i & 4) ? 0.5f : -0.5f);
  }
  const uint16_t faces[12][3] = {{0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}, {0, 1, 5}, {0, 5, 4},
                                 {2, 6, 7}, {2, 7, 3}, {0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}};
  for (const auto& f : faces)
    for (uint16_t v : f) idx.push_back(uint16_t(base + v));
  std::vector<uint8_t> bin(p.size() * 4 + idx.size() * 2);
  std::memcpy(bin.data(), p.data(), p.size() * 4);
  std::memcpy(bin.data() + p.size() * 4, idx.data(), idx.size() * 2);
  json doc = json::parse(R"({
    "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
    "nodes": [{"name": "ground", "mesh": 0}, {"name": "cube", "mesh": 1}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]},
               {"primitives": [{"attributes": {"POSITION": 0}, "indices": 2}]}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 144},
                    {"buffer": 0, "byteOffset": 144, "byteLength": 12},
                    {"buffer": 0, "byteOffset": 156, "byteLength": 72}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 12, "type": "VEC3",
                   "min": [-10, 0, -10], "max": [10, 1, 10]},
                  {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
                  {"bufferView": 2, "componentType": 5123, "count": 36, "type": "SCALAR"}]})");
  doc["buffers"] = json::array({{{"byteLength", bin.size()},
                                 {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
  const std::filesystem::path file = dir / "ground_and_cube.gltf";
  std::ofstream(file) << doc.dump();
  return file.string();
}

json every_technique() {
  return json::array({"none", json{{"name", "shadow_map"}, {"params", {{"size", 256}}}},
                      json{{"name", "pcf_box"}, {"params", {{"size", 256}}}},
                      json{{"name", "pcf_gauss"}, {"params", {{"size", 256}}}},
                      json{{"name", "pcf_jitter"}, {"params", {{"size", 256}}}},
                      json{{"name", "pcss"}, {"params", {{"size", 256}}}},
                      json{{"name", "vsm"}, {"params", {{"size", 256}}}},
                      json{{"name", "esm"}, {"params", {{"size", 256}}}},
                      json{{"name", "evsm"}, {"params", {{"size", 256}}}},
                      json{{"name", "msm"}, {"params", {{"size", 256}}}},
                      json{{"name", "csm_convolution"}, {"params", {{"size", 256}}}},
                      "shadow_volume",
                      json{{"name", "accumulation"}, {"params", {{"samples", 4}, {"size", 128}}}}});
}

void expect_every_technique_ok(const RunOutput& out) {
  ASSERT_EQ(out.records.size(), every_technique().size());
  for (const json& r : out.records) {
    EXPECT_EQ(r["status"], "ok") << r["technique_variant"] << ": " << r.value("reason", "");
  }
}

json experiment(const json& scene) {
  return {{"name", "frustum"},
          {"scenes", json::array({scene})},
          {"techniques", every_technique()},
          {"resolutions", json::array({json::array({48, 32})})},
          {"frames", {{"warmup", 1}, {"timed", 1}}},
          {"reference", {{"spp", 4}, {"cache", false}}}};
}

TEST(LightFrustumScenes, EveryTechniqueRunsOnAGltfWhoseGroundCasts) {
  TempDir dir;
  const std::string file = write_ground_and_cube(dir.path);
  json scene = {{"type", "gltf"},
                {"params", {{"file", file}}},
                {"light", {{"center", {1.0, 6.0, 0.5}}, {"target", {0, 0, 0}}, {"size", 1.0}}}};
  expect_every_technique_ok(run_config(experiment(scene), "frustum_gltf_ground"));
}

TEST(LightFrustumScenes, EveryTechniqueRunsOnATwelveByTwelveSphereGrid) {
  const json scene = {{"type", "sphere_grid"},
                      {"params", {{"grid", 12}, {"slices", 8}, {"stacks", 6}}}};
  expect_every_technique_ok(run_config(experiment(scene), "frustum_grid12"));
}

}  // namespace
}  // namespace sb::test
