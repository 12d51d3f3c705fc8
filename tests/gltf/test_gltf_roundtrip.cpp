// export_glb then load_gltf gives back the same scene: meshes, materials,
// textures, receivers, light and camera.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_access.hpp>

#include "core/scene_types.h"
#include "scenes/gltf_export.h"
#include "scenes/gltf_import.h"
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

using test::TempDir;

Scene default_sphere_grid() {
  const SceneType* t = find_scene_type("sphere_grid");
  return t->build(resolve_params(t->params, nlohmann::json::object(), "test", "/params"));
}

// Two alpha-masked quads sharing a 4x4 texture (straight alpha with partial
// values, so premultiplication would show), over a receiver-only ground.
Scene textured_quads() {
  Scene s;
  s.name = "quads";
  TextureImage t;
  t.name = "checker";
  t.width = 4;
  t.height = 4;
  for (int i = 0; i < 16; ++i) {
    const uint8_t a = i % 3 == 0 ? 0 : i % 3 == 1 ? 255 : 77;
    t.rgba.insert(t.rgba.end(), {uint8_t(i * 16), uint8_t(255 - i * 7), uint8_t(i * 3 + 1), a});
  }
  s.textures.push_back(t);
  for (int q = 0; q < 2; ++q) {
    Mesh m;
    m.name = "leaf_" + std::to_string(q);
    const float x = float(q) * 1.5f;
    m.positions = {{x, 1, 0}, {x + 1, 1, 0}, {x + 1, 2, 0.25f}, {x, 2, 0.25f}};
    m.normals.assign(4, glm::normalize(glm::vec3(0, -0.25f, 1)));
    m.uvs = {{0, 1}, {1, 1}, {1, 0}, {0.1f, 0.3f}};
    m.indices = {0, 1, 2, 0, 2, 3};
    m.albedo = glm::vec3(0.2f, 0.5f, 0.7f);
    m.base_color_texture = 0;
    m.alpha_mode = AlphaMode::Mask;
    m.alpha_cutoff = q == 0 ? 0.3f : 0.5f;
    m.double_sided = true;
    s.meshes.push_back(m);
  }
  Mesh ground;
  ground.name = "ground";
  ground.positions = {{-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}};
  ground.normals.assign(4, glm::vec3(0, 1, 0));
  ground.indices = {0, 1, 2, 0, 2, 3};
  ground.casts_shadow = false;
  s.meshes.push_back(ground);
  s.light = make_area_light({2, 6, 3}, {0.5f, 0.5f, 0}, 3.0f, 1.0f, 2.5f);
  s.camera.eye = {1, 3, 7};
  s.camera.target = {0.5f, 1, 0};
  s.camera.fov_y_degrees = 38;
  s.camera.near_plane = 0.25f;
  s.camera.far_plane = 60;
  s.ambient = glm::vec3(0.1f, 0.2f, 0.3f);
  return s;
}

void expect_near(glm::vec3 a, glm::vec3 b, float tol, const std::string& what) {
  EXPECT_LE(glm::length(a - b), tol) << what << ": (" << a.x << ", " << a.y << ", " << a.z
                                     << ") vs (" << b.x << ", " << b.y << ", " << b.z << ")";
}

void expect_same_scene(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  EXPECT_EQ(a.triangle_count(), b.triangle_count());
  EXPECT_EQ(a.caster_triangle_count(), b.caster_triangle_count());
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    const Mesh& x = a.meshes[i];
    const Mesh& y = b.meshes[i];
    SCOPED_TRACE(x.name);
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.positions, y.positions);  // world-space floats, written and read as they are
    EXPECT_EQ(x.indices, y.indices);
    EXPECT_EQ(x.uvs, y.uvs);
    ASSERT_EQ(x.normals.size(), y.normals.size());
    for (size_t k = 0; k < x.normals.size(); ++k)
      ASSERT_LE(glm::length(x.normals[k] - y.normals[k]), 1e-6f) << "normal " << k;
    EXPECT_EQ(x.albedo, y.albedo);
    EXPECT_EQ(x.casts_shadow, y.casts_shadow);
    EXPECT_EQ(x.alpha_mode, y.alpha_mode);
    EXPECT_EQ(x.alpha_cutoff, y.alpha_cutoff);
    EXPECT_EQ(x.base_color_texture, y.base_color_texture);
    EXPECT_EQ(x.double_sided, y.double_sided);
  }
  ASSERT_EQ(a.textures.size(), b.textures.size());
  for (size_t i = 0; i < a.textures.size(); ++i) {
    EXPECT_EQ(a.textures[i].name, b.textures[i].name);
    EXPECT_EQ(a.textures[i].width, b.textures[i].width);
    EXPECT_EQ(a.textures[i].height, b.textures[i].height);
    EXPECT_EQ(a.textures[i].rgba, b.textures[i].rgba);
  }
  const float tol = 1e-5f * (1.0f + glm::length(a.light.center));
  expect_near(a.light.center, b.light.center, 0, "light center");
  expect_near(a.light.target, b.light.target, tol, "light target");
  expect_near(a.light.half_u, b.light.half_u, 1e-6f, "light half_u");
  expect_near(a.light.half_v, b.light.half_v, 1e-6f, "light half_v");
  EXPECT_EQ(a.light.intensity, b.light.intensity);
  expect_near(a.camera.eye, b.camera.eye, 0, "camera eye");
  expect_near(a.camera.target, b.camera.target, 1e-5f * (1.0f + glm::length(a.camera.eye)),
              "camera target");
  EXPECT_FLOAT_EQ(a.camera.fov_y_degrees, b.camera.fov_y_degrees);
  EXPECT_EQ(a.camera.near_plane, b.camera.near_plane);
  EXPECT_EQ(a.camera.far_plane, b.camera.far_plane);
  const glm::mat4 va = a.camera.view(), vb = b.camera.view();
  for (int c = 0; c < 4; ++c)
    expect_near(glm::vec3(va[c]), glm::vec3(vb[c]), 1e-5f * (1.0f + glm::length(a.camera.eye)),
                "view column " + std::to_string(c));
  EXPECT_EQ(a.ambient, b.ambient);
}

Scene round_trip(const Scene& s, const TempDir& dir) {
  const std::string path = dir / "scene.glb";
  export_glb(s, path);
  return load_gltf(path);
}

TEST(GltfRoundTrip, DefaultSphereGrid) {
  TempDir dir;
  const Scene original = default_sphere_grid();
  const Scene loaded = round_trip(original, dir);
  expect_same_scene(original, loaded);
  EXPECT_FALSE(loaded.meshes.back().casts_shadow);  // the ground stays a receiver
  EXPECT_EQ(loaded.name, "scene");                  // the file's stem
}

TEST(GltfRoundTrip, TexturedAlphaMaskedQuads) {
  TempDir dir;
  const Scene original = textured_quads();
  const Scene loaded = round_trip(original, dir);
  expect_same_scene(original, loaded);
  ASSERT_EQ(loaded.textures.size(), 1u);  // shared by both materials, stored once
  EXPECT_TRUE(loaded.meshes[0].alpha_tested());
  EXPECT_NEAR(loaded.light.width(), 3.0f, 1e-6f);
  EXPECT_NEAR(loaded.light.height(), 1.0f, 1e-6f);
}

TEST(GltfRoundTrip, SecondRoundTripIsStable) {
  TempDir dir;
  const Scene once = round_trip(textured_quads(), dir);
  const Scene twice = round_trip(once, dir);
  expect_same_scene(once, twice);
}

TEST(GltfRoundTrip, ScaleAndLightSizeParameters) {
  TempDir dir;
  const std::string path = dir / "quads.glb";
  export_glb(textured_quads(), path);
  const SceneType* t = find_scene_type("gltf");
  ASSERT_NE(t, nullptr);
  const Scene s = t->build(resolve_params(
      t->params, {{"file", path}, {"scale", 2.0}, {"light_size", 0.5}}, "test", "/params"));
  const Scene original = textured_quads();
  EXPECT_EQ(s.meshes[0].positions[2], 2.0f * original.meshes[0].positions[2]);
  expect_near(s.light.center, 2.0f * original.light.center, 1e-5f, "scaled light center");
  expect_near(s.camera.eye, 2.0f * original.camera.eye, 1e-5f, "scaled eye");
  EXPECT_FLOAT_EQ(s.camera.far_plane, 2.0f * original.camera.far_plane);
  EXPECT_NEAR(s.light.width(), 0.5f, 1e-6f);  // light_size is in the scaled scene's units
  EXPECT_NEAR(s.light.height(), 0.5f, 1e-6f);
  // Default light_size 0 keeps the stored size, scaled with the scene.
  const Scene kept =
      t->build(resolve_params(t->params, {{"file", path}, {"scale", 2.0}}, "test", "/params"));
  EXPECT_NEAR(kept.light.width(), 6.0f, 1e-5f);
}

TEST(GltfRoundTrip, EmptyMeshesAreLeftOut) {
  TempDir dir;
  Scene s = textured_quads();
  Mesh empty;
  empty.name = "empty";
  s.meshes.insert(s.meshes.begin(), empty);
  const Scene loaded = round_trip(s, dir);
  EXPECT_EQ(loaded.meshes.size(), s.meshes.size() - 1);
  EXPECT_EQ(loaded.meshes[0].name, "leaf_0");
}

}  // namespace
}  // namespace sb
