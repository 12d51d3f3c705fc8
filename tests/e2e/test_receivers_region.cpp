// The `receivers` metric region: the measured pixels on meshes that cast no
// shadow, recomputed here from the G-buffer's positions (the ground is the
// plane y = 0) and the written visibility images.
#include <gtest/gtest.h>

#include <cmath>

#include "e2e_util.h"

namespace sb::test {

using core::ImageF;

namespace {

using json = nlohmann::json;

TEST(ReceiversRegion, HoldsTheGroundPixelsAndTheirError) {
  const json config = {
      {"name", "receivers"},
      {"scenes", json::array({small_scene(1e-3)})},
      {"techniques",
       json::array({json{{"name", "shadow_volume"},
                         {"params", {{"silhouettes", "cpu"}, {"silhouette", "smooth"}}}}})},
      {"resolutions", json::array({json::array({160, 120})})},
      {"frames", {{"warmup", 0}, {"timed", 1}}},
      {"reference", {{"spp", 16}}}};
  const auto out = run_config(config, "receivers_region", gl::Backend::OSMesa, true, true);
  ASSERT_EQ(out.summary.failed, 0);
  const std::string variant = "shadow_volume/silhouettes=cpu,silhouette=smooth";
  const auto& m = out.record(variant)["metrics"]["visibility"];
  ASSERT_TRUE(m.contains("receivers")) << m.dump();
  const ImageF positions = out.gbuffer_positions();
  const ImageF v = out.visibility(variant);
  const ImageF ref = out.reference_visibility();
  // The ground faces the light everywhere: none of its pixels is cut by the
  // horizon rule, so the region is exactly the ground's pixels.
  size_t ground = 0;
  double squared = 0.0;
  for (size_t i = 0; i < positions.pixel_count(); ++i) {
    const float* p = &positions.data[4 * i];
    if (p[3] == 0.0f || std::abs(p[1]) > 1e-6f) continue;
    ++ground;
    const double d = double(v.data[i]) - double(ref.data[i]);
    squared += d * d;
  }
  ASSERT_GT(ground, 0u);
  EXPECT_EQ(m["receivers"]["pixel_count"].get<size_t>(), ground);
  EXPECT_LT(ground, m["all"]["pixel_count"].get<size_t>());
  EXPECT_NEAR(m["receivers"]["rmse"].get<double>(), std::sqrt(squared / double(ground)), 1e-6);
}

}  // namespace
}  // namespace sb::test
