// Every generated scene renders at small size: the picture is not blank, and
// each shadow falls where the light says: a ground pixel in the reference's
// shadow has a caster between it and the light, and the shadow map agrees
// with the reference on nearly every pixel.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/scene_types.h"
#include "e2e_util.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "scenes/gltf_export.h"

namespace sb::test {

using core::Bounds;
using core::find_scene_type;
using core::ImageF;
using core::resolve_params;
using core::Scene;
using core::SceneType;

namespace {

using json = nlohmann::json;

bool segment_hits_box(glm::vec3 a, glm::vec3 b, const Bounds& box) {
  float t0 = 0.0f, t1 = 1.0f;
  for (int k = 0; k < 3; ++k) {
    const float d = b[k] - a[k];
    if (std::fabs(d) < 1e-12f) {
      if (a[k] < box.lo[k] || a[k] > box.hi[k]) return false;
      continue;
    }
    float ta = (box.lo[k] - a[k]) / d, tb = (box.hi[k] - a[k]) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

class SceneRenders : public ::testing::TestWithParam<json> {};

TEST_P(SceneRenders, ShadowsFallWhereTheLightSays) {
  const json scene = GetParam();
  const std::string type = scene["type"];
  const json config = {{"name", "scene_" + type},
                       {"scenes", {scene}},
                       {"techniques", {{{"name", "shadow_map"}, {"params", {{"size", 2048}}}}}},
                       {"resolutions", {{160, 120}}},
                       {"frames", {{"warmup", 0}, {"timed", 1}}},
                       {"reference", {{"spp", 64}}}};
  const auto out = run_config(config, "scene_" + type, gl::Backend::OSMesa, true, true);
  ASSERT_EQ(out.summary.failed, 0) << out.records[0].dump(2);
  const auto& r = out.records[0];

  // Not blank: the shaded picture has contrast.
  const ImageF shaded =
      metrics::io::read_image(out.dir + "/" + r["images"]["shaded"].get<std::string>());
  float lo = 1.0f, hi = 0.0f;
  for (float v : shaded.data) lo = std::min(lo, v), hi = std::max(hi, v);
  EXPECT_GT(hi - lo, 0.3f) << type;

  // The same scene on the CPU, to know where the casters are.
  const SceneType* st = find_scene_type(type);
  const Scene s =
      st->build(resolve_params(st->params, scene.value("params", json::object()), "", ""));
  std::vector<Bounds> casters;
  for (const auto& m : s.meshes) {
    if (!m.casts_shadow) continue;
    Bounds b;
    for (const auto& p : m.positions) b.extend(p);
    casters.push_back(b);
  }
  const ImageF positions = out.gbuffer_positions();
  const ImageF ref = out.reference_visibility();
  size_t ground = 0, shadowed = 0, explained = 0;
  for (size_t i = 0; i < positions.pixel_count(); ++i) {
    const glm::vec3 p(positions.data[4 * i], positions.data[4 * i + 1], positions.data[4 * i + 2]);
    if (positions.data[4 * i + 3] == 0.0f || std::fabs(p.y) > 1e-4f) continue;  // the ground
    ++ground;
    if (ref.data[i] >= 0.5f) continue;
    ++shadowed;
    for (const auto& b : casters)
      if (segment_hits_box(p, s.light.center, b)) {
        ++explained;
        break;
      }
  }
  EXPECT_GT(ground, positions.pixel_count() / 4) << type << ": the ground is in view";
  EXPECT_GT(shadowed, ground / 100) << type << ": shadows are visible on the ground";
  EXPECT_LT(shadowed, ground * 9 / 10) << type;
  // A 0.5-visibility shadow of an area light may come from a caster a little
  // off the centre's ray: allow a few such pixels.
  EXPECT_GT(double(explained), 0.97 * double(shadowed)) << type;

  const ImageF sm = out.visibility("shadow_map/size=2048");
  EXPECT_LT(metrics::compare(sm, ref).frac_over_01, 0.25) << type;
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, SceneRenders,
    ::testing::Values(json{{"type", "sphere_grid"}, {"params", {{"grid", 3}}}},
                      json{{"type", "foliage"}, {"params", {{"trees", 2}}}},
                      json{{"type", "jeep"}, {"params", {{"count", 2}}}},
                      json{{"type", "gltf"},
                           {"params",
                            {{"file", SHADOWBENCH_SOURCE_DIR "/configs/models/jeep.glb"}}}}),
    [](const auto& param_info) { return param_info.param["type"].template get<std::string>(); });

}  // namespace
}  // namespace sb::test

namespace sb::test {
namespace {

// Export then load gives the same rendered visibility, pixel for pixel.
TEST(GltfRoundTrip, SameRenderedVisibility) {
  const SceneType* st = find_scene_type("jeep");
  const nlohmann::json params = {{"count", 2}};
  const Scene s = st->build(resolve_params(st->params, params, "", ""));
  const std::string glb = process_temp_path("shadowbench_roundtrip") + ".glb";
  export_glb(s, glb);
  const auto render = [](const json& scene, const std::string& name) {
    const json config = {{"name", name},
                         {"scenes", {scene}},
                         {"techniques", {{{"name", "shadow_map"}, {"params", {{"size", 1024}}}}}},
                         {"resolutions", {{128, 96}}},
                         {"frames", {{"warmup", 0}, {"timed", 1}}},
                         {"reference", {{"spp", 16}}}};
    return run_config(config, name);
  };
  const auto a = render(json{{"type", "jeep"}, {"params", params}}, "roundtrip_generated");
  const auto b = render(json{{"type", "gltf"}, {"params", {{"file", glb}}}}, "roundtrip_loaded");
  const ImageF va = a.visibility("shadow_map/size=1024"), vb = b.visibility("shadow_map/size=1024");
  ASSERT_TRUE(va.same_shape(vb));
  EXPECT_EQ(va.data, vb.data);
  EXPECT_EQ(a.records[0]["scene"]["triangles"], b.records[0]["scene"]["triangles"]);
}

}  // namespace
}  // namespace sb::test
