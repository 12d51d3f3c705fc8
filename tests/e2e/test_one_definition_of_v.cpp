// One definition of V (docs/design.md): pixels whose tangent plane cuts the
// light rectangle are left out of every error and counted; pixels facing away
// from the whole light are V = 0 for everyone; and the shaded comparison uses
// the same V as the visibility comparison.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

#include "../gltf/gltf_builder.h"
#include "e2e_util.h"
#include "metrics/light_horizon.h"
#include "scenes/gltf_export.h"
#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"

namespace sb::test {

using core::AreaLight;
using core::ImageF;
using core::Scene;

namespace {

// Convex casters alone, with no ground: nothing occludes any point but its
// own surface, so where the whole light is above a point's tangent plane the
// true V is exactly 1, and where it is wholly below, 0. A tilted box (planar
// receivers whose planes cut the light) and a sphere (the terminator band),
// under a light as large as they are and close.
std::string write_convex_scene(const std::filesystem::path& dir) {
  Scene s;
  s.meshes.push_back(make_box("tilted_box", {-1.2f, 0.0f, 0.0f}, {0.6f, 0.6f, 0.6f},
                              glm::mat3(glm::rotate(glm::mat4(1.0f), 0.6f, {0.3f, 0.2f, 1.0f}))));
  s.meshes.push_back(make_uv_sphere("sphere", {1.2f, 0.0f, 0.0f}, 0.7f, 24, 16));
  s.light.center = {0.0f, 2.2f, 0.0f};
  s.light.half_u = {2.0f, 0.0f, 0.0f};
  s.light.half_v = {0.0f, 0.0f, 2.0f};
  s.light.target = {0.0f, 0.0f, 0.0f};
  s.camera.eye = {0.0f, -0.4f, 5.0f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  const auto file = dir / "convex.glb";
  export_glb(s, file.string());
  return file.string();
}

json convex_experiment(const std::string& file) {
  return {{"name", "one_v"},
          {"scenes", json::array({{{"type", "gltf"}, {"params", {{"file", file}}}}})},
          {"techniques",
           json::array({"none", json{{"name", "shadow_map"}, {"params", {{"size", 512}}}}})},
          {"resolutions", json::array({json::array({96, 64})})},
          {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"spp", 64}, {"cache", false}}}};
}

TEST(OneDefinitionOfV, PixelsWhoseTangentPlaneCutsTheLightAreLeftOutAndCounted) {
  TempDir dir;
  const auto out = run_config(convex_experiment(write_convex_scene(dir.path)), "one_v_convex",
                              gl::Backend::OSMesa, true, /*write_gbuffer=*/true);
  ASSERT_EQ(out.summary.ok, 2);
  const json& none = out.record("none");
  const ImageF ref = out.reference_visibility();
  // Where the reference is fractional here, only the horizon made it so.
  size_t fractional = 0;
  for (float v : ref.data) fractional += v > 0.0f && v < 1.0f ? 1 : 0;
  ASSERT_GT(fractional, 50u) << "the light must cut many tangent planes";
  EXPECT_GE(none["reference"]["horizon_cut_pixels"].get<size_t>(), fractional);
  // Everywhere else none, shadow_map and the reference agree.
  EXPECT_EQ(none["metrics"]["visibility"]["all"]["rmse"].get<double>(), 0.0);
  EXPECT_EQ(none["metrics"]["visibility"]["all"]["pixel_count"].get<size_t>(),
            ref.pixel_count() - none["reference"]["horizon_cut_pixels"].get<size_t>());
  EXPECT_LT(out.record("shadow_map/size=512")["metrics"]["visibility"]["all"]["mae"].get<double>(),
            0.01);
  // The count is the pixels whose plane has light corners on both sides.
  const ImageF positions = out.gbuffer_positions();
  const ImageF normals = out.image(none, "gbuffer_normals");
  const AreaLight light = [] {
    AreaLight l;
    l.center = {0.0f, 2.2f, 0.0f};
    l.half_u = {2.0f, 0.0f, 0.0f};
    l.half_v = {0.0f, 0.0f, 2.0f};
    return l;
  }();
  size_t cut = 0;
  for (size_t i = 0; i < positions.pixel_count(); ++i) {
    if (positions.data[i * 4 + 3] == 0.0f) continue;
    const glm::vec3 p(positions.data[i * 4], positions.data[i * 4 + 1], positions.data[i * 4 + 2]);
    const glm::vec3 n(normals.data[i * 3], normals.data[i * 3 + 1], normals.data[i * 3 + 2]);
    int above = 0;
    for (float s : {0.0f, 1.0f})
      for (float t : {0.0f, 1.0f}) above += glm::dot(n, light.point(s, t) - p) > 0.0f ? 1 : 0;
    cut += above > 0 && above < 4 ? 1 : 0;
  }
  EXPECT_EQ(none["reference"]["horizon_cut_pixels"].get<size_t>(), cut);
}

TEST(OneDefinitionOfV, NoneHasNoShadedErrorWhereNoCasterShadows) {
  TempDir dir;
  const auto out = run_config(convex_experiment(write_convex_scene(dir.path)), "one_v_shaded");
  ASSERT_EQ(out.summary.ok, 2);
  // No caster shadows any measured pixel of this scene: attached pixels are
  // V = 0 in both shaded images, the rest V = 1 in both.
  const json& shaded = out.record("none")["metrics"]["shaded"]["all"];
  EXPECT_EQ(shaded["max_error"].get<double>(), 0.0);
  EXPECT_GT(out.record("none")["reference"]["attached_shadow_pixels"].get<size_t>(), 20u);
}

}  // namespace
}  // namespace sb::test
