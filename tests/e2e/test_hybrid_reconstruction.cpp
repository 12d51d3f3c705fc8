// hybrid_reconstruction (shadow volumes rebuilt from a depth map,
// shadow_volume/depth_map_cliffs.h): on a closed scene under a near-point
// light it agrees with shadow_volume, both hard from the light's centre, up
// to the map's resolution; on foliage, whose leaves are open and
// alpha-tested, it runs where shadow_volume is skipped.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "e2e_util.h"

namespace sb::test {
namespace {

using json = nlohmann::json;

json experiment(const json& scene, const json& techniques) {
  return {{"name", "hybrid_reconstruction"},
          {"scenes", json::array({scene})},
          {"techniques", techniques},
          {"resolutions", json::array({json::array({320, 240})})},
          {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"spp", 16}}}};
}

// Whether a pixel lies within `radius` pixels of both a shadowed (V < ½)
// and a lit pixel of `v`: on the shadow's edge.
bool near_edge(const ImageF& v, int x, int y, int radius) {
  bool dark = false, lit = false;
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx) {
      const int px = std::clamp(x + dx, 0, v.width - 1), py = std::clamp(y + dy, 0, v.height - 1);
      (v.data[size_t(py) * size_t(v.width) + size_t(px)] < 0.5f ? dark : lit) = true;
    }
  return dark && lit;
}

TEST(HybridReconstruction, OnAClosedSceneItAgreesWithShadowVolumeUpToTheMapsResolution) {
  const json scene = {{"type", "sphere_grid"}, {"params", {{"grid", 3}, {"light_size", 0.01}}}};
  const auto out = run_config(
      experiment(scene, json::array({"shadow_volume", "hybrid_reconstruction"})), "hybrid_closed");
  ASSERT_EQ(out.summary.failed, 0);
  const ImageF volume = out.visibility("shadow_volume");
  const ImageF hybrid = out.visibility("hybrid_reconstruction");
  int shadowed = 0, differ = 0, off_edge = 0;
  for (int y = 0; y < volume.height; ++y)
    for (int x = 0; x < volume.width; ++x) {
      const size_t i = size_t(y) * size_t(volume.width) + size_t(x);
      shadowed += volume.data[i] < 0.5f ? 1 : 0;
      if ((volume.data[i] < 0.5f) == (hybrid.data[i] < 0.5f)) continue;
      ++differ;
      // A 1024² map fitted to the grid puts about one texel on a pixel here:
      // two pixels from the edge is beyond the map's resolution.
      if (!near_edge(volume, x, y, 2)) ++off_edge;
    }
  std::printf("shadowed %d, differing %d, of which %d more than 2 px from the edge\n", shadowed,
              differ, off_edge);
  EXPECT_GT(shadowed, 3000);
  EXPECT_LT(differ, shadowed / 40);
  // Stray pixels where a camera ray grazes the reconstructed staircase (the
  // spheres' terminators): measured 15 of 76,800.
  EXPECT_LT(off_edge, 40);
}

TEST(HybridReconstruction, OnFoliageItRunsWhereShadowVolumeIsSkipped) {
  const json scene = {{"type", "foliage"}, {"params", {{"light_size", 0.01}}}};
  const auto out = run_config_with(
      experiment(scene, json::array({"none", "shadow_volume", "hybrid_reconstruction",
                                     json{{"name", "shadow_map"}, {"params", {{"size", 1024}}}}})),
      "hybrid_foliage", [](RunOptions& o) { o.pass_detail = gl::PassDetail::Fine; });
  const json& volume = out.record("shadow_volume");
  EXPECT_EQ(volume["status"], "skipped");
  EXPECT_NE(volume["reason"].get<std::string>().find("closed"), std::string::npos);
  const json& hybrid = out.record("hybrid_reconstruction");
  ASSERT_EQ(hybrid["status"], "ok") << hybrid.value("reason", "");
  const auto rmse = [&](const std::string& t) {
    return out.record(t)["metrics"]["visibility"]["all"]["rmse"].get<double>();
  };
  std::printf("foliage rmse: none %.4f, shadow_map %.4f, hybrid_reconstruction %.4f\n",
              rmse("none"), rmse("shadow_map/size=1024"), rmse("hybrid_reconstruction"));
  // Its leaves cast shadows: most of the error of casting none is gone.
  EXPECT_LT(rmse("hybrid_reconstruction"), 0.5 * rmse("none"));
  // Its reconstruction and read-back are passes of their own.
  const json& passes = hybrid["timing"]["pass_order"];
  for (const char* pass : {"shadow_map", "read_back", "reconstruct", "upload", "stencil"})
    EXPECT_NE(std::find(passes.begin(), passes.end(), pass), passes.end()) << pass;
}

}  // namespace
}  // namespace sb::test
