// technique.gpu_bytes through a real run: the peak GPU storage each
// technique made through the gl::make_* helpers, against the sum of the
// textures its documentation names (docs/shadow_maps.md, docs/parameters.md),
// computed by hand from their formats' bytes per texel; and what the harness
// holds on the GPU for the needs it declares, against the scene's counts
// times the bytes an element of each upload takes.
#include <gtest/gtest.h>

#include <memory>

#include "e2e_util.h"
#include "gl/objects.h"
#include "plugin/registry.h"
#include "record/job_record.h"

namespace sb::test {

using core::Params;
using core::Scene;
using plugin::DerivedData;
using plugin::FrameInputs;
using plugin::NeedProvider;
using plugin::Needs;
using plugin::Registry;
using plugin::Technique;
using record::JobRecord;

namespace {

using json = nlohmann::json;

// The record of the technique called `name` whose params include `params`.
const json& record_of(const RunOutput& out, const std::string& name, const json& params) {
  for (const json& r : out.records) {
    if (r["technique"]["name"] != name) continue;
    bool match = true;
    for (const auto& [key, value] : params.items()) match &= r["technique"]["params"][key] == value;
    if (match) return r;
  }
  throw std::runtime_error("no record of " + name + " " + params.dump());
}

// technique.gpu_bytes, or with `key` another of its members.
std::int64_t gpu_bytes(const RunOutput& out, const std::string& name, const json& params,
                       const std::string& key = "gpu_bytes") {
  const json& r = record_of(out, name, params);
  EXPECT_EQ(r["status"], "ok") << r.dump();
  // What the record says is what its reader reads.
  const JobRecord back = JobRecord::from_json(r);
  EXPECT_EQ(back.technique.gpu_bytes, r["technique"]["gpu_bytes"].get<std::int64_t>());
  return r["technique"].at(key).get<std::int64_t>();
}

TEST(GpuBytes, AreTheSumOfTheDocumentedTexturesOfEachTechnique) {
  const json config = {
      {"name", "gpu_bytes"},
      {"scenes", json::array({small_scene(0.5)})},
      {"techniques",
       json::array({"none",
                    {{"name", "shadow_map"}, {"params", {{"size", 64}}}},
                    {{"name", "shadow_map"}, {"params", {{"size", 64}, {"depth_format", "16"}}}},
                    {{"name", "vsm"}, {"params", {{"size", 64}}}},
                    {{"name", "vsm"},
                     {"params", {{"size", 64}, {"format", "16f"}, {"prefilter", "box"}, {"k", 3}}}},
                    {{"name", "shadow_volume"}, {"params", {{"silhouettes", "cpu"}}}}})},
      {"resolutions", json::array({json::array({64, 48})})},
      {"frames", {{"warmup", 0}, {"timed", 1}}},
      {"reference", {{"spp", 4}}}};
  const RunOutput out = run_config(config, "gpu_bytes");
  ASSERT_EQ(out.summary.failed, 0);

  // none draws nothing of its own.
  EXPECT_EQ(gpu_bytes(out, "none", json::object()), 0);
  // shadow_map: one 64² depth map, GL_DEPTH_COMPONENT32F (4 bytes) or
  // GL_DEPTH_COMPONENT16 (2 bytes).
  EXPECT_EQ(gpu_bytes(out, "shadow_map", {{"size", 64}, {"depth_format", "32f"}}), 64 * 64 * 4);
  EXPECT_EQ(gpu_bytes(out, "shadow_map", {{"size", 64}, {"depth_format", "16"}}), 64 * 64 * 2);
  // vsm: the depth map and the moments z, z² (GL_RG32F, 8 bytes); with a
  // prefilter, the filter's scratch of the moments' format too (GL_RG16F, 4
  // bytes, for format 16f).
  EXPECT_EQ(gpu_bytes(out, "vsm", {{"size", 64}, {"prefilter", "none"}}),
            64 * 64 * 4 + 64 * 64 * 8);
  EXPECT_EQ(gpu_bytes(out, "vsm", {{"size", 64}, {"prefilter", "box"}}),
            64 * 64 * 4 + 64 * 64 * 4 + 64 * 64 * 4);
  // Shadow volumes from CPU silhouettes stream their vertices (vec4s, 16
  // bytes each): some, and whole ones.
  const std::int64_t volumes =
      gpu_bytes(out, "shadow_volume", {{"silhouettes", "cpu"}}, "gpu_own_bytes");
  EXPECT_GT(volumes, 0);
  EXPECT_EQ(volumes % 16, 0);
}

// The bytes an element of each upload the harness makes for a need takes,
// from their layouts (written out here, not read from the code that
// uploads): GL_TRIANGLES_ADJACENCY indices of 4 bytes, 6 a triangle
// (gl/gpu_scene.h); a silhouette edge's std430 record of 4 vec4s of floats
// (plugin/silhouette_edges.h).
constexpr std::int64_t kAdjacencyBytesPerCasterTriangle = 6 * 4;
constexpr std::int64_t kSilhouetteBytesPerEdge = 4 * 4 * 4;

TEST(GpuBytes, ChargeEachTechniqueWhatTheHarnessHoldsForTheNeedsItDeclares) {
  // 3×3 closed UV spheres of 8 slices and 6 stacks, each 2·8·(6−1) = 80
  // triangles, over a ground that casts nothing. A closed mesh has every
  // edge between two of its triangles: 3 edges a triangle, each shared.
  constexpr std::int64_t kCasterTriangles = 9 * 2 * 8 * (6 - 1);  // 720
  constexpr std::int64_t kEdges = kCasterTriangles * 3 / 2;       // 1080
  json scene = small_scene(0.5);
  scene["params"]["slices"] = 8;
  scene["params"]["stacks"] = 6;
  const json config = {
      {"name", "gpu_need_bytes"},
      {"scenes", json::array({scene})},
      {"techniques", json::array({{{"name", "shadow_volume"}},
                                  {{"name", "penumbra_maps"}, {"params", {{"size", 64}}}},
                                  {{"name", "shadow_map"}, {"params", {{"size", 64}}}}})},
      {"resolutions", json::array({json::array({64, 48})})},
      {"frames", {{"warmup", 0}, {"timed", 1}}},
      {"reference", {{"spp", 4}}}};
  const RunOutput out = run_config(config, "gpu_need_bytes");
  ASSERT_EQ(out.summary.failed, 0);
  ASSERT_EQ(out.records.at(0)["scene"]["caster_triangles"], kCasterTriangles);

  // shadow_volume (silhouettes in a geometry shader) makes no storage of its
  // own: its volumes come out of the harness's adjacency buffer, which it
  // declares (edge_adjacency). Its other needs hold nothing on the GPU.
  const json& volume = record_of(out, "shadow_volume", json::object())["technique"];
  EXPECT_EQ(volume["gpu_own_bytes"], 0);
  EXPECT_EQ(volume["gpu_need_bytes"],
            json({{"edge_adjacency", kCasterTriangles * kAdjacencyBytesPerCasterTriangle}}));
  EXPECT_EQ(gpu_bytes(out, "shadow_volume", json::object()), 720 * 24);

  // penumbra_maps: its 64² GL_DEPTH_COMPONENT32F map and GL_R32F penumbra
  // buffer (4 bytes a texel each), and the edges (silhouette_edges).
  const json& penumbra = record_of(out, "penumbra_maps", {{"size", 64}})["technique"];
  EXPECT_EQ(penumbra["gpu_own_bytes"], 64 * 64 * 4 + 64 * 64 * 4);
  EXPECT_EQ(penumbra["gpu_need_bytes"],
            json({{"silhouette_edges", kEdges * kSilhouetteBytesPerEdge}}));
  EXPECT_EQ(gpu_bytes(out, "penumbra_maps", {{"size", 64}}), 32768 + 1080 * 64);

  // shadow_map declares only caster_closedness, which holds nothing on the
  // GPU: charged nothing besides its map.
  const json& map = record_of(out, "shadow_map", {{"size", 64}})["technique"];
  EXPECT_EQ(map["gpu_need_bytes"], json::object());
  EXPECT_EQ(gpu_bytes(out, "shadow_map", {{"size", 64}}), 64 * 64 * 4);
}

// A plugin's need whose GPU stage keeps a buffer of `kept` bytes and frees
// a 16² GL_RGBA8 scratch texture (1 KiB) before it returns.
NeedProvider buffer_need(const std::string& name, GLsizeiptr kept,
                         std::vector<std::string> requires_needs) {
  NeedProvider p;
  p.name = name;
  p.summary = "a buffer of " + std::to_string(kept) + " bytes";
  p.requires_needs = std::move(requires_needs);
  p.upload = [name, kept](const Scene&, const gl::GpuScene&, DerivedData& data) {
    const gl::Texture scratch = gl::make_texture_2d(GL_RGBA8, 16, 16);
    data.put<gl::Buffer>(name, std::make_shared<gl::Buffer>(gl::make_buffer(kept, nullptr)));
  };
  return p;
}

// Makes nothing; V = 1.
class Lit final : public Technique {
 public:
  void prepare(const FrameInputs& /*in*/) override {}
  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    auto pass = timer.scope("clear");
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glClearColor(1, 1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
  }
};

TEST(GpuBytes, APluginNeedsUploadIsChargedToWhoDeclaresItOrANeedThatRequiresIt) {
  Registry registry;
  registry.add_provider(buffer_need("table", 1000, {}));
  registry.add_provider(buffer_need("table_index", 24, {"table"}));
  const auto lit = [](const std::string& name, Needs needs) {
    return plugin::TechniqueInfo{
        name, "test", "clears V to 1", std::move(needs), {}, [](const Params&) {
          return std::make_unique<Lit>();
        }};
  };
  registry.add(lit("direct", Needs{"table"}));
  registry.add(lit("indirect", Needs{"table_index"}));
  registry.add(lit("neither", Needs{}));
  const json config = {{"name", "plugin_need_bytes"},
                       {"scenes", json::array({small_scene(0.5)})},
                       {"techniques", json::array({"direct", "indirect", "neither"})},
                       {"resolutions", json::array({json::array({32, 24})})},
                       {"frames", {{"warmup", 0}, {"timed", 1}}},
                       {"reference", {{"spp", 4}}}};
  const RunOutput out = run_with_registry(config, registry, "plugin_need_bytes");
  ASSERT_EQ(out.summary.ok, 3);
  // What each upload keeps, not its scratch; shared, and charged to each.
  const json& direct = out.record("direct")["technique"];
  EXPECT_EQ(direct["gpu_own_bytes"], 0);
  EXPECT_EQ(direct["gpu_need_bytes"], json({{"table", 1000}}));
  EXPECT_EQ(direct["gpu_bytes"], 1000);
  const json& indirect = out.record("indirect")["technique"];
  EXPECT_EQ(indirect["gpu_need_bytes"], json({{"table", 1000}, {"table_index", 24}}));
  EXPECT_EQ(indirect["gpu_bytes"], 1024);
  const json& neither = out.record("neither")["technique"];
  EXPECT_EQ(neither["gpu_need_bytes"], json::object());
  EXPECT_EQ(neither["gpu_bytes"], 0);
}

}  // namespace
}  // namespace sb::test
