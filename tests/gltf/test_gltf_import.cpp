// What load_gltf reads from files it did not write: external files, the node
// hierarchy, index types, strips and fans, sparse and normalised accessors,
// materials, cameras and lights.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "config/identity.h"
#include "core/scene_types.h"
#include "record/spec_changes.h"
#include "scenes/gltf_export.h"
#include "scenes/gltf_import.h"
#include "tests/gltf/gltf_builder.h"

namespace sb {

using core::AlphaMode;
using core::find_scene_type;
using core::Mesh;
using core::resolve_params;
using core::Scene;
using core::SceneType;
using core::TextureImage;

namespace {

using test::GltfBuilder;
using test::input_error;
using test::json;
using test::TempDir;

constexpr int kFloat = 5126, kU8 = 5121, kU16 = 5123, kU32 = 5125, kI8 = 5120;

// One triangle in the z = 0 plane, counter-clockwise seen from +z.
const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

glm::vec3 face_normal(const Mesh& m, size_t t) {
  const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                  c = m.positions[m.indices[3 * t + 2]];
  return glm::normalize(glm::cross(b - a, c - a));
}

void expect_vec(glm::vec3 a, glm::vec3 b, float tol = 1e-5f) {
  EXPECT_LE(glm::length(a - b), tol) << "(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x
                                     << ", " << b.y << ", " << b.z << ")";
}

// Unpacks a .glb into .gltf + .bin + one .png per image, all in `dir`
// (images in a subfolder), the way a hand-made asset would look.
std::string unpack_glb(const std::vector<uint8_t>& glb, const TempDir& dir) {
  const uint32_t json_len = uint32_t(glb[12]) | uint32_t(glb[13]) << 8 | uint32_t(glb[14]) << 16 |
                            uint32_t(glb[15]) << 24;
  json doc = json::parse(glb.begin() + 20, glb.begin() + 20 + json_len);
  const std::vector<uint8_t> bin(glb.begin() + 20 + json_len + 8, glb.end());
  std::filesystem::create_directories(dir.path / "textures");
  for (size_t i = 0; i < doc.value("images", json::array()).size(); ++i) {
    json& img = doc["images"][i];
    const json& v = doc["bufferViews"][img["bufferView"].get<size_t>()];
    const size_t off = v.value("byteOffset", size_t(0)), len = v["byteLength"].get<size_t>();
    const std::string name = "textures/image " + std::to_string(i) + ".png";
    test::write_bytes(dir.path / name,
                      std::vector<uint8_t>(bin.begin() + long(off), bin.begin() + long(off + len)));
    img.erase("bufferView");
    img.erase("mimeType");
    img["uri"] = "textures/image%20" + std::to_string(i) + ".png";
  }
  doc["buffers"][0]["uri"] = "scene.bin";
  test::write_bytes(dir.path / "scene.bin", bin);
  std::ofstream(dir / "scene.gltf") << doc.dump(1);
  return dir / "scene.gltf";
}

Scene textured_scene() {
  Scene s;
  TextureImage t;
  t.name = "tex";
  t.width = 2;
  t.height = 3;
  for (int i = 0; i < 6; ++i)
    t.rgba.insert(t.rgba.end(), {uint8_t(40 * i), 7, 200, uint8_t(i * 50)});
  s.textures.push_back(t);
  Mesh m;
  m.name = "quad";
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.normals.assign(4, {0, 0, 1});
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.base_color_texture = 0;
  m.alpha_mode = AlphaMode::Mask;
  s.meshes.push_back(m);
  return s;
}

TEST(GltfImport, ExternalBufferAndImagesInTheSameFolder) {
  TempDir dir;
  const Scene original = textured_scene();
  const std::string gltf = unpack_glb(export_glb_bytes(original), dir);
  const Scene s = load_gltf(gltf);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].positions, original.meshes[0].positions);
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].rgba, original.textures[0].rgba);
  // The same, from another working directory: nothing is looked up there.
  const auto cwd = std::filesystem::current_path();
  std::filesystem::current_path(std::filesystem::temp_directory_path());
  EXPECT_NO_THROW(load_gltf(gltf));
  std::filesystem::current_path(cwd);
}

// sha256sum's digest of a file: another implementation than the importer's.
std::string sha256sum_of(const std::string& file) {
  std::string out;
  if (FILE* p = popen(("sha256sum '" + file + "'").c_str(), "r")) {
    char buf[128];
    while (fgets(buf, sizeof buf, p) != nullptr) out += buf;
    pclose(p);
  }
  return out.substr(0, 64);
}

TEST(GltfImport, TheSceneListsEveryFileItReadWithItsSha256) {
  // What a job's identity holds instead of the path (config/identity.h):
  // the file, then its buffer and images, named relative to its folder as
  // their URIs name them (%20 decoded), each once.
  TempDir dir;
  const std::string gltf = unpack_glb(export_glb_bytes(textured_scene()), dir);
  const Scene s = load_gltf(gltf);
  ASSERT_EQ(s.inputs.size(), 3u);
  EXPECT_EQ(s.inputs[0].path, gltf);
  EXPECT_EQ(s.inputs[0].name, "");
  EXPECT_EQ(s.inputs[0].sha256, sha256sum_of(gltf));
  EXPECT_EQ(s.inputs[1].name, "scene.bin");
  EXPECT_EQ(s.inputs[1].sha256, sha256sum_of(dir / "scene.bin"));
  EXPECT_EQ(s.inputs[2].name, "textures/image 0.png");
  EXPECT_EQ(s.inputs[2].sha256, sha256sum_of(dir / "textures/image 0.png"));
  // A .glb holds everything: one file.
  const std::string glb = dir / "scene.glb";
  test::write_bytes(glb, export_glb_bytes(textured_scene()));
  const Scene packed = load_gltf(glb);
  ASSERT_EQ(packed.inputs.size(), 1u);
  EXPECT_EQ(packed.inputs[0].sha256, sha256sum_of(glb));
}

TEST(GltfImport, ATextureEditedInPlaceChangesTheScenesIdentityNamingIt) {
  // A job's identity holds what the import read (config/identity.h): a
  // texture whose bytes change, under the same name, changes it, and a
  // rerun's reason names the texture.
  TempDir dir, other;
  const std::string gltf = unpack_glb(export_glb_bytes(textured_scene()), dir);
  const nlohmann::json before = config::file_identity(gltf, load_gltf(gltf).inputs);
  Scene recoloured = textured_scene();
  recoloured.textures[0].rgba[0] = 255;
  unpack_glb(export_glb_bytes(recoloured), other);
  std::filesystem::copy_file(other / "textures/image 0.png", dir / "textures/image 0.png",
                             std::filesystem::copy_options::overwrite_existing);
  const nlohmann::json after = config::file_identity(gltf, load_gltf(gltf).inputs);
  EXPECT_EQ(after["sha256"], before["sha256"]);  // the .gltf is as it was
  EXPECT_EQ(after["reads"]["scene.bin"], before["reads"]["scene.bin"]);
  EXPECT_EQ(after["reads"]["textures/image 0.png"], sha256sum_of(dir / "textures/image 0.png"));
  EXPECT_NE(after["reads"]["textures/image 0.png"], before["reads"]["textures/image 0.png"]);
  const std::vector<std::string> changes =
      record::spec_changes({{"file", before}}, {{"file", after}}, {{"file", "scene.gltf"}});
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_EQ(
      changes[0].rfind("file textures/image 0.png of scene.gltf: content changed (sha256 ", 0), 0u)
      << changes[0];
}

TEST(GltfImport, SymbolicLinksOutOfTheFolderAreRefused) {
  TempDir outside, dir;
  GltfBuilder b;
  b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}});
  b.node({{"mesh", 0}});
  b.save_gltf(outside / "x.gltf", "secret.bin");
  std::filesystem::create_symlink(outside.path / "secret.bin", dir.path / "link.bin");
  const std::string path = b.save_gltf(dir / "x.gltf", "link.bin");
  // link.bin (written through the link) is a valid buffer, but it lives outside.
  const std::string msg = input_error([&] { load_gltf(path); });
  EXPECT_NE(msg.find("buffer 0 uri"), std::string::npos) << msg;
  EXPECT_NE(msg.find("outside the glTF file's folder"), std::string::npos) << msg;
}

TEST(GltfImport, HierarchyWithTrsAndMatrixIsFlattened) {
  TempDir dir;
  GltfBuilder b;
  b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}}, "tri");
  // parent: translate (10, 0, 0), rotate 90° about y, scale 2; child: matrix translate (0, 0, 1).
  const double h = std::sqrt(0.5);
  b.node({{"name", "parent"},
          {"translation", {10, 0, 0}},
          {"rotation", {0, h, 0, h}},
          {"scale", {2, 2, 2}},
          {"children", {1}}});
  b.node({{"name", "child"},
          {"mesh", 0},
          {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1}}},
         false);
  const Scene s = load_gltf(b.save_gltf(dir / "h.gltf"));
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].name, "child");
  // local p -> (p + (0,0,1)) * 2 rotated about y by 90° (x -> -z, z -> x) + (10,0,0)
  expect_vec(s.meshes[0].positions[0], {12, 0, 0});
  expect_vec(s.meshes[0].positions[1], {12, 0, -2});
  expect_vec(s.meshes[0].positions[2], {12, 2, 0});
}

TEST(GltfImport, MirrorTransformKeepsFrontFacesCounterClockwise) {
  TempDir dir;
  GltfBuilder b;
  const std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  b.mesh({{"attributes",
           {{"POSITION", b.positions(kTriangle)},
            {"NORMAL", b.accessor(normals, kFloat, "VEC3", 3)}}}});
  b.node({{"mesh", 0}, {"scale", {-1, 1, 1}}});
  const Scene s = load_gltf(b.save_gltf(dir / "m.gltf"));
  expect_vec(s.meshes[0].positions[1], {-1, 0, 0});
  expect_vec(face_normal(s.meshes[0], 0), {0, 0, 1});
  expect_vec(s.meshes[0].normals[0], {0, 0, 1});
}

TEST(GltfImport, EveryIndexTypeAndNonIndexed) {
  TempDir dir;
  const std::vector<float> quad = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  GltfBuilder b;
  const int pos = b.positions(quad);
  const std::vector<uint8_t> i8 = {0, 1, 2, 0, 2, 3};
  const std::vector<uint16_t> i16 = {0, 1, 2, 0, 2, 3};
  const std::vector<uint32_t> i32 = {0, 1, 2, 0, 2, 3};
  b.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", b.accessor(i8, kU8, "SCALAR", 6)}});
  b.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", b.accessor(i16, kU16, "SCALAR", 6)}});
  b.mesh({{"attributes", {{"POSITION", pos}}}, {"indices", b.accessor(i32, kU32, "SCALAR", 6)}});
  b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}});
  for (int i = 0; i < 4; ++i) b.node({{"mesh", i}});
  const Scene s = load_gltf(b.save_glb(dir / "i.glb"));
  ASSERT_EQ(s.meshes.size(), 4u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(s.meshes[size_t(i)].triangle_count(), 2u);
    // No normals in the file: flat normals, one vertex per corner.
    EXPECT_EQ(s.meshes[size_t(i)].positions.size(), 6u);
    expect_vec(s.meshes[size_t(i)].normals[4], {0, 0, 1});
    expect_vec(s.meshes[size_t(i)].positions[5], {0, 1, 0});
  }
  EXPECT_EQ(s.meshes[3].triangle_count(), 1u);
}

TEST(GltfImport, StripsAndFansBecomeConsistentlyWoundLists) {
  TempDir dir;
  GltfBuilder b;
  // strip 0,1,2,3 over a quad; fan around the centre of a square
  const std::vector<float> strip = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  const std::vector<float> fan = {0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 1, 0, -1, -1, 0};
  b.mesh({{"attributes", {{"POSITION", b.positions(strip)}}}, {"mode", 5}});
  b.mesh({{"attributes", {{"POSITION", b.positions(fan)}}}, {"mode", 6}});
  b.node({{"mesh", 0}});
  b.node({{"mesh", 1}});
  const Scene s = load_gltf(b.save_gltf(dir / "s.gltf"));
  ASSERT_EQ(s.meshes[0].triangle_count(), 2u);
  ASSERT_EQ(s.meshes[1].triangle_count(), 3u);
  for (const Mesh& m : s.meshes)
    for (size_t t = 0; t < m.triangle_count(); ++t) expect_vec(face_normal(m, t), {0, 0, 1});
}

TEST(GltfImport, SparseAndNormalizedAccessors) {
  TempDir dir;
  GltfBuilder b;
  // POSITION as normalized bytes (KHR_mesh_quantization style), one vertex moved by sparse.
  const std::vector<int8_t> pos = {0, 0, 0, 127, 0, 0, 0, 127, 0};
  const int p = b.accessor(pos, kI8, "VEC3", 3, true);
  const std::vector<uint16_t> uv = {0, 0, 65535, 0, 0, 32768};
  const int t = b.accessor(uv, kU16, "VEC2", 3, true);
  const std::vector<uint8_t> sparse_index = {2};
  const std::vector<int8_t> sparse_value = {0, 127, 127};
  const int iv = b.view(sparse_index.data(), 1);
  const int vv = b.view(sparse_value.data(), 3);
  b.doc["accessors"][size_t(p)]["sparse"] = {
      {"count", 1},
      {"indices", {{"bufferView", iv}, {"componentType", kU8}}},
      {"values", {{"bufferView", vv}}}};
  // A second primitive whose POSITION has no bufferView: zeros plus sparse values.
  const std::vector<uint16_t> zi = {1, 2};
  const std::vector<float> zv = {2, 0, 0, 0, 2, 0};
  const int ziv = b.view(zi.data(), 4), zvv = b.view(zv.data(), 24);
  b.arr("accessors")
      .push_back({{"componentType", kFloat},
                  {"count", 3},
                  {"type", "VEC3"},
                  {"sparse",
                   {{"count", 2},
                    {"indices", {{"bufferView", ziv}, {"componentType", kU16}}},
                    {"values", {{"bufferView", zvv}}}}}});
  b.mesh({{"attributes", {{"POSITION", p}, {"TEXCOORD_0", t}}}});
  b.mesh({{"attributes", {{"POSITION", int(b.doc["accessors"].size() - 1)}}}});
  b.node({{"mesh", 0}});
  b.node({{"mesh", 1}});
  const Scene s = load_gltf(b.save_gltf(dir / "q.gltf"));
  expect_vec(s.meshes[0].positions[1], {1, 0, 0});
  expect_vec(s.meshes[0].positions[2], {0, 1, 1});  // from the sparse value
  ASSERT_EQ(s.meshes[0].uvs.size(), 3u);
  EXPECT_FLOAT_EQ(s.meshes[0].uvs[1].x, 1.0f);
  EXPECT_NEAR(s.meshes[0].uvs[2].y, 32768.0f / 65535.0f, 1e-7f);
  expect_vec(s.meshes[1].positions[1], {2, 0, 0});
  expect_vec(s.meshes[1].positions[2], {0, 2, 0});
}

TEST(GltfImport, MaterialsTexturesAndTextureTransform) {
  TempDir dir;
  // Borrow an encoded PNG from an export.
  const std::vector<uint8_t> exported = export_glb_bytes(textured_scene());
  const uint32_t json_len = exported[12] | exported[13] << 8;
  const json ex = json::parse(exported.begin() + 20, exported.begin() + 20 + json_len);
  const json& iv = ex["bufferViews"][ex["images"][0]["bufferView"].get<size_t>()];
  const std::vector<uint8_t> png(
      exported.begin() + long(20 + json_len + 8 + iv["byteOffset"].get<size_t>()),
      exported.begin() + long(20 + json_len + 8 + iv["byteOffset"].get<size_t>() +
                              iv["byteLength"].get<size_t>()));

  GltfBuilder b;
  const int image_view = b.view(png.data(), png.size());
  b.arr("images").push_back({{"bufferView", image_view}, {"mimeType", "image/png"}});
  b.arr("textures").push_back({{"source", 0}});
  b.arr("textures").push_back({{"source", 0}});  // a second texture, same image
  b.arr("materials")
      .push_back({{"pbrMetallicRoughness",
                   {{"baseColorFactor", {0.25, 0.5, 0.75, 1}},
                    {"baseColorTexture",
                     {{"index", 0},
                      {"extensions",
                       {{"KHR_texture_transform", {{"offset", {0.5, 0}}, {"scale", {2, 2}}}}}}}}}},
                  {"alphaMode", "MASK"},
                  {"alphaCutoff", 0.25},
                  {"doubleSided", true}});
  b.arr("materials")
      .push_back({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 1}}}}},
                  {"alphaMode", "BLEND"}});
  const std::vector<float> uv = {0, 0, 1, 0, 0, 1};
  const int pos = b.positions(kTriangle), tc = b.accessor(uv, kFloat, "VEC2", 3);
  b.mesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", tc}}}, {"material", 0}});
  b.mesh({{"attributes", {{"POSITION", pos}, {"TEXCOORD_0", tc}}}, {"material", 1}});
  b.mesh({{"attributes", {{"POSITION", pos}}}});
  for (int i = 0; i < 3; ++i) b.node({{"mesh", i}});
  const Scene s = load_gltf(b.save_glb(dir / "mat.glb"));
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].rgba, textured_scene().textures[0].rgba);
  const Mesh& m0 = s.meshes[0];
  expect_vec(m0.albedo, {0.25f, 0.5f, 0.75f});
  EXPECT_EQ(m0.base_color_texture, 0);
  EXPECT_EQ(m0.alpha_mode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(m0.alpha_cutoff, 0.25f);
  EXPECT_TRUE(m0.double_sided);
  EXPECT_FLOAT_EQ(m0.uvs[1].x, 2.5f);  // uv * 2 + (0.5, 0)
  EXPECT_FLOAT_EQ(m0.uvs[2].y, 2.0f);
  EXPECT_EQ(s.meshes[1].base_color_texture, 0);
  EXPECT_EQ(s.meshes[1].alpha_mode, AlphaMode::Mask);  // BLEND is treated as MASK at 0.5
  EXPECT_FLOAT_EQ(s.meshes[1].alpha_cutoff, 0.5f);
  expect_vec(s.meshes[2].albedo, {1, 1, 1});  // glTF's default material
  EXPECT_EQ(s.meshes[2].base_color_texture, -1);
}

TEST(GltfImport, InstancesNamesAndDefaultCameraAndLight) {
  TempDir dir;
  GltfBuilder b;
  b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}}, "shared");
  b.node({{"name", "left"}, {"mesh", 0}, {"translation", {-2, 0, 0}}});
  b.node({{"mesh", 0}, {"translation", {2, 0, 0}}});
  b.doc.erase("scenes");  // no scenes: every root node is drawn
  const Scene s = load_gltf(b.save_gltf(dir / "inst.gltf"));
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].name, "left");
  EXPECT_EQ(s.meshes[1].name, "shared");
  EXPECT_TRUE(s.meshes[0].casts_shadow);
  // The default camera sees every vertex.
  const glm::mat4 vp = s.camera.projection(4.0f / 3.0f) * s.camera.view();
  for (const Mesh& m : s.meshes)
    for (const glm::vec3& p : m.positions) {
      const glm::vec4 c = vp * glm::vec4(p, 1);
      EXPECT_LT(std::fabs(c.x / c.w), 1.0f);
      EXPECT_LT(std::fabs(c.y / c.w), 1.0f);
      EXPECT_GT(c.w, s.camera.near_plane);
    }
  // The default light is above the scene, aimed at its centre.
  EXPECT_GT(s.light.center.y, s.bounds().hi.y);
  expect_vec(s.light.target, s.bounds().center());
  EXPECT_GT(s.light.width(), 0.0f);
}

TEST(GltfImport, CameraAndSpotLightNodes) {
  TempDir dir;
  GltfBuilder b;
  b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}});
  b.node({{"mesh", 0}});
  b.arr("cameras").push_back(
      {{"type", "orthographic"},
       {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 9}}}});
  b.arr("cameras").push_back(
      {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.05}}}});
  b.node({{"camera", 0}});  // orthographic: skipped
  const double h = std::sqrt(0.5);
  b.node({{"camera", 1}, {"translation", {0, 0, 10}}});  // looks down -z at the triangle
  b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "spot"}, {"intensity", 500}, {"spot", json::object()}}};
  // rotation -90° about x: local -z points down
  b.node({{"translation", {0, 8, 0}},
          {"rotation", {-h, 0, 0, h}},
          {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  const Scene s = load_gltf(b.save_gltf(dir / "c.gltf"));
  expect_vec(s.camera.eye, {0, 0, 10});
  expect_vec(glm::normalize(s.camera.target - s.camera.eye), {0, 0, -1});
  EXPECT_NEAR(s.camera.fov_y_degrees, 0.5f * 180.0f / std::numbers::pi_v<float>, 1e-4f);
  EXPECT_FLOAT_EQ(s.camera.near_plane, 0.05f);
  EXPECT_GT(s.camera.far_plane, 10.0f);  // infinite zfar: far enough for the scene
  expect_vec(s.light.center, {0, 8, 0});
  expect_vec(glm::normalize(s.light.target - s.light.center), {0, -1, 0});
  EXPECT_FLOAT_EQ(s.light.intensity, 1.0f);  // photometric units are not used
  EXPECT_NEAR(glm::dot(s.light.half_u, s.light.direction()), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(s.light.half_v, s.light.direction()), 0.0f, 1e-6f);
}

TEST(GltfImport, PointAndDirectionalLights) {
  TempDir dir;
  for (const char* type : {"point", "directional"}) {
    GltfBuilder b;
    b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}});
    b.node({{"mesh", 0}});
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", type}}};
    b.node({{"translation", {0, 0, 5}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    const Scene s = load_gltf(b.save_gltf(dir / (std::string(type) + ".gltf")));
    SCOPED_TRACE(type);
    expect_vec(s.light.target, s.bounds().center());
    if (std::string(type) == "point") expect_vec(s.light.center, {0, 0, 5});
    // directional lights shine along the node's -z, from outside the bounds
    if (std::string(type) == "directional")
      expect_vec(glm::normalize(s.light.target - s.light.center), {0, 0, -1});
    // A directional light is the sun, 0.53° across unless the file says.
    EXPECT_EQ(s.light.is_sun(), std::string(type) == "directional");
    if (s.light.is_sun()) {
      EXPECT_NEAR(glm::degrees(s.light.angular_diameter), 0.53f, 1e-5f);
    }
  }
}

TEST(GltfImport, DirectionalLightsAreTheSunWithTheirSizeFromExtras) {
  TempDir dir;
  GltfBuilder b;
  b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}});
  b.node({{"mesh", 0}});
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "directional"}}};
  b.node({{"rotation", {-0.3826834, 0, 0, 0.9238795}},  // -45° about x: shining down and away
          {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}},
          {"extras", {{"shadowbench_light", {{"angular_diameter", 2.5}}}}}});
  const Scene s = load_gltf(b.save_gltf(dir / "sun.gltf"));
  ASSERT_TRUE(s.light.is_sun());
  EXPECT_NEAR(glm::degrees(s.light.angular_diameter), 2.5f, 1e-5f);
  expect_vec(s.light.to_sun(), glm::normalize(glm::vec3(0, 1, 1)));
  // Written back, it stays the sun with its size and direction.
  export_glb(s, dir / "again.glb");
  const Scene again = load_gltf(dir / "again.glb");
  ASSERT_TRUE(again.light.is_sun());
  EXPECT_NEAR(glm::degrees(again.light.angular_diameter), 2.5f, 1e-5f);
  expect_vec(again.light.to_sun(), s.light.to_sun());

  b.doc["nodes"][1]["extras"]["shadowbench_light"]["angular_diameter"] = 0;
  const std::string msg = input_error([&] { load_gltf(b.save_gltf(dir / "bad.gltf")); });
  EXPECT_NE(msg.find("angular_diameter: expected the sun's diameter in degrees in [0.0001, 90]"),
            std::string::npos)
      << msg;
}

TEST(GltfImport, GltfSceneTypeNeedsAFile) {
  const SceneType* t = find_scene_type("gltf");
  ASSERT_NE(t, nullptr);
  const std::string msg =
      input_error([&] { resolve_params(t->params, json::object(), "c.json", "/scenes/0/params"); });
  EXPECT_EQ(msg, "c.json: at /scenes/0/params: missing required key \"file\" in this object");
}

}  // namespace
}  // namespace sb
