// hybrid_reconstruction (shadow volumes rebuilt from a depth map,
// shadow_volume/depth_map_cliffs.h): on a closed scene under a near-point
// light it agrees with the ray-traced reference and with shadow_volume, hard
// from the light's centre, up to the map's resolution; on foliage, whose leaves are open and
// alpha-tested, it runs where shadow_volume is skipped.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>

#include "e2e_util.h"

namespace sb::test {

using core::ImageF;
using run::RunOptions;

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

// Where `v` and `truth` disagree on V < ½: how many pixels, and how many of
// them lie more than two pixels from `truth`'s shadow edge.
struct HardDisagreement {
  int shadowed = 0;  // pixels with V < ½ in `truth`
  int differ = 0;
  int off_edge = 0;
};

HardDisagreement disagreement(const ImageF& truth, const ImageF& v) {
  HardDisagreement d;
  for (int y = 0; y < truth.height; ++y)
    for (int x = 0; x < truth.width; ++x) {
      const size_t i = size_t(y) * size_t(truth.width) + size_t(x);
      d.shadowed += truth.data[i] < 0.5f ? 1 : 0;
      if ((truth.data[i] < 0.5f) == (v.data[i] < 0.5f)) continue;
      ++d.differ;
      if (!near_edge(truth, x, y, 2)) ++d.off_edge;
    }
  return d;
}

// Under a light 0.01 wide the true shadow is hard from the light's centre up
// to a penumbra of a hundredth of a pixel here, so the ray-traced reference
// (16 samples per pixel) and shadow_volume draw the same V < ½; the
// hybrid must draw it too, but for a band along the edge as wide as the
// map's texels (a 1024² map fitted to the grid puts about one texel on a
// pixel here: two pixels from the edge is beyond its resolution).
TEST(HybridReconstruction, OnAClosedSceneItAgreesWithTheReferenceAndShadowVolumeUpToTheMapsTexels) {
  const json scene = {{"type", "sphere_grid"}, {"params", {{"grid", 3}, {"light_size", 0.01}}}};
  const auto out = run_config(
      experiment(scene, json::array({"shadow_volume", "hybrid_reconstruction"})), "hybrid_closed");
  ASSERT_EQ(out.summary.failed, 0);
  const ImageF reference = out.reference_visibility();
  const ImageF volume = out.visibility("shadow_volume");
  const ImageF hybrid = out.visibility("hybrid_reconstruction");
  for (const auto& [name, truth] :
       {std::pair<std::string, const ImageF&>{"reference", reference}, {"shadow_volume", volume}}) {
    SCOPED_TRACE(name);
    const HardDisagreement d = disagreement(truth, hybrid);
    std::printf("against %s: shadowed %d, differing %d, of which %d more than 2 px from the edge\n",
                name.c_str(), d.shadowed, d.differ, d.off_edge);
    EXPECT_GT(d.shadowed, 3000);
    EXPECT_LT(d.differ, d.shadowed / 40);
    // Stray pixels where a camera ray grazes the reconstructed staircase (the
    // spheres' terminators): measured 15 of 76,800 against shadow_volume.
    EXPECT_LT(d.off_edge, 40);
  }
  // The hard reference itself: shadow_volume, exact from the light's centre,
  // draws the reference's V < ½ but for its sampled edge pixels.
  const HardDisagreement exact = disagreement(reference, volume);
  std::printf("shadow_volume against the reference: differing %d, %d off the edge\n", exact.differ,
              exact.off_edge);
  EXPECT_EQ(exact.off_edge, 0);
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
