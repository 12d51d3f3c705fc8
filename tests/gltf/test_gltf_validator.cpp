// Exports are valid glTF for the Khronos validator (npm gltf-validator,
// pinned in tools/gltf-validator; scripts/test.sh installs it). Skipped when
// node or the package is missing.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>

#include "core/scene_types.h"
#include "scenes/gltf_export.h"
#include "tests/gltf/gltf_builder.h"

namespace sb {

using core::AlphaMode;
using core::find_scene_type;
using core::make_area_light;
using core::Mesh;
using core::resolve_params;
using core::Scene;
using core::SceneType;
using core::TextureImage;

namespace {

using test::json;
using test::TempDir;

const std::string kTool = std::string(SHADOWBENCH_SOURCE_DIR) + "/tools/gltf-validator";

std::string run(const std::string& cmd, int& status) {
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  std::string out;
  std::array<char, 512> buf{};
  while (pipe != nullptr && fgets(buf.data(), int(buf.size()), pipe) != nullptr) out += buf.data();
  status = pipe == nullptr ? -1 : pclose(pipe);
  return out;
}

class GltfValidator : public ::testing::Test {
 protected:
  void SetUp() override {
    int status = 0;
    run("command -v node", status);
    if (status != 0) GTEST_SKIP() << "node is not installed";
    if (!std::filesystem::exists(kTool + "/node_modules/gltf-validator/package.json"))
      GTEST_SKIP() << "gltf-validator is not installed: npm install --prefix " << kTool;
  }

  // Exports `scene`, validates it and expects no errors (warnings are listed).
  void expect_valid(const Scene& scene, const std::string& name) {
    const std::string path = dir_ / (name + ".glb");
    export_glb(scene, path);
    int status = 0;
    const std::string out = run("node '" + kTool + "/validate.js' '" + path + "'", status);
    const json report =
        json::parse(out.substr(std::min(out.find('{'), out.size())), nullptr, false);
    ASSERT_TRUE(report.is_object()) << out;
    EXPECT_EQ(report["errors"], 0) << report.dump(1);
    EXPECT_EQ(report["warnings"], 0) << report.dump(1);
  }
  TempDir dir_;
};

TEST_F(GltfValidator, DefaultSphereGrid) {
  const SceneType* t = find_scene_type("sphere_grid");
  expect_valid(t->build(resolve_params(t->params, json::object(), "test", "/params")),
               "sphere_grid");
}

TEST_F(GltfValidator, TexturedAlphaMaskedScene) {
  Scene s;
  TextureImage tex;
  tex.name = "leaf";
  tex.width = 3;
  tex.height = 2;
  for (int i = 0; i < 6; ++i)
    tex.rgba.insert(tex.rgba.end(), {uint8_t(i * 40), 200, 30, uint8_t(i * 51)});
  s.textures.push_back(tex);
  Mesh m;
  m.name = "leaf";
  m.positions = {{0, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  m.normals.assign(4, {0, 0, 1});
  m.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.base_color_texture = 0;
  m.alpha_mode = AlphaMode::Mask;
  m.alpha_cutoff = 0.4f;
  m.double_sided = true;
  s.meshes.push_back(m);
  Mesh ground = m;
  ground.name = "ground";
  ground.positions = {{-4, 0, -4}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}};
  ground.normals.assign(4, {0, 1, 0});
  ground.uvs.clear();
  ground.base_color_texture = -1;
  ground.alpha_mode = AlphaMode::Opaque;
  ground.double_sided = false;
  ground.casts_shadow = false;
  s.meshes.push_back(ground);
  s.light = make_area_light({1, 5, 2}, {0, 0, 0}, 2, 1);
  expect_valid(s, "textured");
}

}  // namespace
}  // namespace sb
