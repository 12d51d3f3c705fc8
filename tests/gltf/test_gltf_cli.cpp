// `shadowbench scene export` and `scene info` as a user runs them.
#include <gtest/gtest.h>

#include "scenes/gltf_import.h"
#include "tests/config/cli_runner.h"
#include "tests/gltf/gltf_builder.h"

namespace sb {

using core::Scene;

namespace {

using test::run_cli;
using test::TempDir;

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

TEST(GltfCli, ExportShortAndJsonSpecs) {
  TempDir dir;
  auto r = run_cli("scene export sphere_grid:grid=3,light_size=0.5,slices=8 " + (dir / "a.glb"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  Scene a = load_gltf(dir / "a.glb");
  EXPECT_EQ(a.meshes.size(), 10u);
  EXPECT_NEAR(a.light.width(), 0.5f, 1e-6f);
  r = run_cli(R"(scene export '{"type":"sphere_grid","params":{"grid":2}}' )" + (dir / "b.glb"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(load_gltf(dir / "b.glb").meshes.size(), 5u);
  // glTF to glTF, the path relative to the working directory.
  r = run_cli("scene export gltf:file=" + (dir / "b.glb") + ",scale=2 " + (dir / "c.glb"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(load_gltf(dir / "c.glb").meshes.size(), 5u);
}

TEST(GltfCli, BadSpecsExitWithCode2NamingTheParameter) {
  TempDir dir;
  const std::string out = " " + (dir / "x.glb");
  auto r = run_cli("scene export sphere_grid:grid=x" + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.output, "scene spec: at /params/grid: parameter 'grid'")) << r.output;
  r = run_cli(R"(scene export '{"type":"sphere_grid","params":{"gird":3}}')" + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.output, "unknown parameter 'gird'")) << r.output;
  r = run_cli("scene export teapot" + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.output, "unknown scene type 'teapot'")) << r.output;
  r = run_cli("scene export sphere_grid:grid" + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.output, "expected NAME=VALUE")) << r.output;
  r = run_cli("scene export gltf" + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(
      contains(r.output, "scene spec: at /params: missing required key \"file\" in this object"))
      << r.output;
  r = run_cli("scene export sphere_grid");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "x.glb"));
}

TEST(GltfCli, InfoOnFilesAndSpecs) {
  TempDir dir;
  ASSERT_EQ(run_cli("scene export sphere_grid:grid=2 " + (dir / "g.glb")).exit_code, 0);
  auto r = run_cli("scene info " + (dir / "g.glb"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "5 meshes (4 closed), 3042 triangles (3040 casting)")) << r.output;
  r = run_cli("scene info sphere_grid:grid=2");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "3042 triangles")) << r.output;
  const std::string broken =
      std::string(SHADOWBENCH_SOURCE_DIR) + "/tests/gltf/corpus/index_out_of_range.gltf";
  r = run_cli("scene info " + broken);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.output, broken + ": at accessor 1")) << r.output;
}

}  // namespace
}  // namespace sb
