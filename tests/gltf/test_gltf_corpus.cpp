// Broken files (tests/gltf/corpus, made by make_corpus.py) each give an
// InputError naming the file and the place; mangled files never crash.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <random>

#include "core/scene_types.h"
#include "scenes/gltf_export.h"
#include "scenes/gltf_import.h"
#include "tests/gltf/gltf_builder.h"

namespace sb {

using core::AlphaMode;
using core::find_scene_type;
using core::InputError;
using core::resolve_params;
using core::Scene;
using core::SceneType;
using core::TextureImage;

namespace {

using test::input_error;
using test::json;
using test::TempDir;

const std::string kCorpus = std::string(SHADOWBENCH_SOURCE_DIR) + "/tests/gltf/corpus/";

struct Case {
  const char* file;
  const char* where;  // the place the message must name
  const char* what;   // and a fragment of what is wrong
};

const Case kCases[] = {
    {"truncated.glb", "at GLB header", "file is truncated"},
    {"glb_version1.glb", "at GLB header", "version 1 is not supported"},
    {"glb_bin_overrun.glb", "at GLB BIN chunk", "runs past the end of the file"},
    {"json_syntax.gltf", "at JSON line 19, column 11", "syntax error"},
    {"version1.gltf", "at asset", "version '1.0' is not supported"},
    {"required_draco.gltf", "at extensionsRequired", "'KHR_draco_mesh_compression'"},
    {"accessor_past_view.gltf", "at accessor 0 (POSITION of mesh 'tri' (0) primitive 0)",
     "need 48 bytes from byte 0 of bufferView 0, which has only 36"},
    {"accessor_offset_past_view.gltf", "at accessor 0",
     "byteOffset 40 is past the end of bufferView 0"},
    {"view_past_buffer.gltf", "at bufferView 1", "run past the end of buffer 0"},
    {"bad_component_type.gltf", "at accessor 0", "componentType 1234 is not one of"},
    {"huge_count.gltf", "at accessor 0", "count 4000000000 exceeds the limit"},
    {"wrong_type.gltf", "at accessor 0", "expected type VEC3, found VEC2"},
    {"index_out_of_range.gltf", "at accessor 1 (indices of mesh 'tri' (0) primitive 0)",
     "index 7 (element 2) is out of range: POSITION has 3 vertices"},
    {"sparse_index_out_of_range.gltf", "at accessor 0", "sparse index 9 is out of range"},
    {"absolute_uri.gltf", "at buffer 0 uri", "absolute paths are not allowed"},
    {"dotdot_uri.gltf", "at buffer 0 uri", "'..' segments are not allowed"},
    {"dotdot_escaped_uri.gltf", "at buffer 0 uri", "'..' segments are not allowed"},
    {"file_uri.gltf", "at buffer 0 uri", "'file:' URIs are not allowed"},
    {"http_image_uri.gltf", "at image 0 uri", "'http:' URIs are not allowed"},
    {"missing_buffer.gltf", "at buffer 0 uri", "file 'missing.bin' not found"},
    {"image_not_png.gltf", "at image 'junk' (0)", "neither a PNG nor a JPEG"},
    {"mode_points.gltf", "at mesh 'dots' (0) primitive 0", "mode POINTS (0) is not supported"},
    {"no_position.gltf", "at mesh 'tri' (0) primitive 0", "has no POSITION attribute"},
    {"node_cycle.gltf", "at node 'wheel' (0)", "the node hierarchy has a cycle"},
    {"node_self_parent.gltf", "at node 'tri' (0)", "is its own child"},
    {"node_two_parents.gltf", "at node 'shared' (2)", "has two parents"},
    {"node_bad_mesh.gltf", "at node 'tri' (0)", "mesh 5 does not exist"},
    {"camera_yfov_zero.gltf", "at camera 'cam' (0)", "yfov 0.0 is outside (0, pi)"},
};

TEST(GltfCorpus, EveryBrokenFileNamesFileAndPlace) {
  size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(kCorpus))
    files += e.path().extension() == ".gltf" || e.path().extension() == ".glb";
  EXPECT_EQ(files, std::size(kCases)) << "a corpus file without a case (or the reverse)";
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.file);
    const std::string path = kCorpus + c.file;
    const std::string msg = input_error([&] { load_gltf(path); });
    EXPECT_EQ(msg.rfind(path + ": " + c.where, 0), 0u) << msg;
    EXPECT_NE(msg.find(c.what), std::string::npos) << msg;
  }
}

TEST(GltfCorpus, MissingFileAndNonGltf) {
  TempDir dir;
  EXPECT_NE(input_error([&] { load_gltf(dir / "nope.glb"); }).find("file not found"),
            std::string::npos);
  { std::ofstream empty(dir / "empty.gltf"); }
  EXPECT_NE(input_error([&] { load_gltf(dir / "empty.gltf"); }).find("file is empty"),
            std::string::npos);
  std::ofstream(dir / "array.gltf") << "[1, 2]";
  EXPECT_NE(input_error([&] { load_gltf(dir / "array.gltf"); }).find("expected a glTF object"),
            std::string::npos);
  std::ofstream(dir / "deep.gltf") << R"({"asset": {"version": "2.0"}, "extras": )"
                                   << std::string(100, '[') << std::string(100, ']') << "}";
  EXPECT_NE(input_error([&] { load_gltf(dir / "deep.gltf"); }).find("nested more than"),
            std::string::npos);
}

// Loads `bytes` from a file; fine when it loads or throws InputError.
// Counts outcomes by the place the error names, to see how deep the fuzz gets.
void load_must_not_crash(const TempDir& dir, const std::string& name,
                         const std::vector<uint8_t>& bytes, const std::string& what,
                         std::map<std::string, int>& outcomes) {
  test::write_bytes(dir.path / name, bytes);
  try {
    load_gltf(dir / name);
    ++outcomes["loaded"];
  } catch (const InputError& e) {
    const std::string w = e.where().substr(0, e.where().find_first_of(" (0123456789"));
    ++outcomes[w.empty() ? "(tinygltf)" : w];
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": not an InputError: " << e.what();
  }
}

void print(const char* test, const std::map<std::string, int>& outcomes) {
  std::string line;
  for (const auto& [k, v] : outcomes) line += " " + k + "=" + std::to_string(v);
  std::printf("%s:%s\n", test, line.c_str());
}

std::vector<uint8_t> small_textured_glb() {
  const SceneType* t = find_scene_type("sphere_grid");
  Scene s = t->build(resolve_params(t->params,
                                    {{"grid", 1}, {"slices", 4}, {"stacks", 3}, {"light_size", 1}},
                                    "test", "/params"));
  TextureImage tex;
  tex.width = tex.height = 2;
  tex.rgba = {255, 0, 0, 255, 0, 255, 0, 0, 0, 0, 255, 128, 9, 9, 9, 255};
  s.textures.push_back(tex);
  s.meshes[0].base_color_texture = 0;
  s.meshes[0].alpha_mode = AlphaMode::Mask;
  s.meshes[0].uvs.assign(s.meshes[0].positions.size(), glm::vec2(0.25f, 0.75f));
  return export_glb_bytes(s);
}

TEST(GltfFuzz, TruncatedAndGarbledGlb) {
  TempDir dir;
  const std::vector<uint8_t> glb = small_textured_glb();
  ASSERT_NO_THROW(load_gltf([&] {
    test::write_bytes(dir.path / "ok.glb", glb);
    return dir / "ok.glb";
  }()));
  std::map<std::string, int> outcomes;
  for (size_t n = 0; n < glb.size(); n += std::max<size_t>(1, glb.size() / 300))
    load_must_not_crash(dir, "cut.glb", std::vector<uint8_t>(glb.begin(), glb.begin() + long(n)),
                        "truncated at " + std::to_string(n), outcomes);
  std::mt19937 rng(12345);
  for (int i = 0; i < 1500; ++i) {
    std::vector<uint8_t> g = glb;
    const int flips = 1 + int(rng() % 4);
    for (int f = 0; f < flips; ++f) {
      // Half of the flips land in the first 64 bytes and the JSON, where they matter most.
      const size_t at = rng() % 2 ? rng() % std::min<size_t>(g.size(), 1200) : rng() % g.size();
      g[at] = uint8_t(rng() % 2 ? rng() : g[at] ^ (1u << (rng() % 8)));
    }
    load_must_not_crash(dir, "garbled.glb", g, "garble " + std::to_string(i), outcomes);
  }
  print("truncated and garbled", outcomes);
  EXPECT_GT(outcomes["loaded"], 0);
}

// Replaces random JSON values (indices, counts, offsets, types, URIs) with
// hostile ones: the structure stays valid JSON, the content does not.
// The 1500 mutations in three parts, one gtest each (the whole took 33 s
// under ASan in a clean-clone CI run, over scripts/check-test-times.py's
// 30 s): every part draws the same sequence and loads its third.
class GltfFuzzPart : public ::testing::TestWithParam<int> {};

TEST_P(GltfFuzzPart, MutatedJsonValues) {
  const int part = GetParam();
  TempDir dir;
  const std::vector<uint8_t> glb = small_textured_glb();
  const uint32_t json_len = glb[12] | glb[13] << 8 | glb[14] << 16;
  const json doc = json::parse(glb.begin() + 20, glb.begin() + 20 + json_len);
  const std::vector<uint8_t> bin(glb.begin() + 20 + json_len + 8, glb.end());
  json base = doc;
  base["buffers"][0]["uri"] = "data:application/octet-stream;base64," + test::base64(bin);

  std::vector<json::json_pointer> leaves;
  const json flat = base.flatten();
  for (auto it = flat.begin(); it != flat.end(); ++it)
    if (it.key().find("/buffers/0/uri") != 0) leaves.emplace_back(it.key());
  const json hostile[] = {-1,
                          0,
                          1,
                          2,
                          3,
                          7,
                          255,
                          65535,
                          65536,
                          1e300,
                          -1e300,
                          4294967295.0,
                          4000000000,
                          1.5,
                          "",
                          "x",
                          "VEC4",
                          "MAT4",
                          "/etc/passwd",
                          "../x.bin",
                          "http://x/y",
                          nullptr,
                          true,
                          json::array(),
                          json::object(),
                          json::array({1, 2, 3})};
  std::map<std::string, int> outcomes;
  std::mt19937 rng(777);
  for (int i = 0; i < 1500; ++i) {
    const bool mine = i / 500 == part;
    json d = base;
    std::string what;
    for (int k = 0, n = 1 + int(rng() % 3); k < n; ++k) {
      const auto& p = leaves[rng() % leaves.size()];
      const json& v = hostile[rng() % std::size(hostile)];
      // Replace the leaf or, sometimes, its parent object/array.
      const auto target = rng() % 4 == 0 && !p.parent_pointer().empty() ? p.parent_pointer() : p;
      if (!d.contains(target)) continue;  // an earlier mutation replaced its parent
      d[target] = v;
      what += target.to_string() + "=" + v.dump() + " ";
    }
    if (!mine) continue;
    const std::string text = d.dump();
    load_must_not_crash(dir, "mutated.gltf", std::vector<uint8_t>(text.begin(), text.end()), what,
                        outcomes);
  }
  print("mutated", outcomes);
  EXPECT_GT(outcomes["loaded"], 0);
}
INSTANTIATE_TEST_SUITE_P(GltfFuzz, GltfFuzzPart, ::testing::Values(0, 1, 2));

}  // namespace
}  // namespace sb
