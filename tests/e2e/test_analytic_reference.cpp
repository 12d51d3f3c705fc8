// A sphere grid's "analytic" option reaches the reference through the real
// run: the rasterised G-buffer is the same, the reference differs (it
// occludes with exact spheres), its cache key differs, and the record says
// how many casters were traced as shapes.
#include <gtest/gtest.h>

#include <cstring>

#include "e2e_util.h"

namespace sb::test {

using core::ImageF;

namespace {

using json = nlohmann::json;

TEST(AnalyticReference, TheOptionReachesTheReferenceAndTheRecord) {
  json scene = small_scene(0.5);
  scene["params"]["slices"] = 8;
  scene["params"]["stacks"] = 6;
  scene["params"]["analytic"] = json::array({false, true});
  const json config = {{"name", "analytic"},
                       {"scenes", json::array({scene})},
                       {"techniques", json::array({"none"})},
                       {"resolutions", json::array({json::array({96, 72})})},
                       {"frames", {{"warmup", 0}, {"timed", 1}}},
                       {"reference", {{"spp", 16}}}};
  const auto out = run_config(config, "analytic_reference", gl::Backend::OSMesa, true,
                              /*write_gbuffer=*/true);
  ASSERT_EQ(out.summary.ok, 2);
  ASSERT_EQ(out.records.size(), 2u);
  const json* tess = nullptr;
  const json* analytic = nullptr;
  for (const json& r : out.records)
    (r["scene"]["params"]["analytic"].get<bool>() ? analytic : tess) = &r;
  ASSERT_TRUE(tess != nullptr && analytic != nullptr);
  EXPECT_EQ((*tess)["scene"]["analytic_casters"], 0);
  EXPECT_EQ((*analytic)["scene"]["analytic_casters"], 9);
  EXPECT_EQ((*tess)["scene"]["caster_triangles"], (*analytic)["scene"]["caster_triangles"]);
  EXPECT_NE((*tess)["reference"]["cache_key"], (*analytic)["reference"]["cache_key"]);

  // The same points (the triangles'), two references.
  const ImageF pt = out.image(*tess, "gbuffer_positions");
  const ImageF pa = out.image(*analytic, "gbuffer_positions");
  ASSERT_TRUE(pt.same_shape(pa));
  EXPECT_EQ(std::memcmp(pt.data.data(), pa.data.data(), pt.data.size() * sizeof(float)), 0);
  const ImageF vt = out.image(*tess, "reference_visibility");
  const ImageF va = out.image(*analytic, "reference_visibility");
  ASSERT_TRUE(vt.same_shape(va));
  // The exact spheres are larger than their inscribed polyhedra: they hide
  // more of the light, never less, on the ground they shadow.
  size_t darker = 0, lighter = 0;
  for (size_t i = 0; i < vt.data.size(); ++i) {
    darker += va.data[i] < vt.data[i] - 0.2f;
    lighter += va.data[i] > vt.data[i] + 0.2f;
  }
  EXPECT_GT(darker, 20u);
  EXPECT_LT(lighter, darker / 10 + 1);
}

}  // namespace
}  // namespace sb::test
