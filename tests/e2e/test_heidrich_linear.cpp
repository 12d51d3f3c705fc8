// Linear lights and heidrich_linear (soft shadow maps for linear lights,
// shadow_map/heidrich_linear.cpp), against the closed form of a plate's
// shadow under a segment: the plate projected from a ground point onto the
// light's plane hides the part of the segment inside its projection.
//   - across the plate's edge the penumbra is a linear ramp, and the
//     technique is within 0.05 of it more than 2 texels from the hard
//     shadows' boundaries (where it switches between its maps);
//   - along the edge the shadow is hard, for the technique too;
//   - it needs a segment: a rectangle or a point light skips it, with the
//     reason; techniques that need a rectangle skip a segment.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "../gltf/gltf_builder.h"
#include "common/light_frustum.h"
#include "core/scene_types.h"
#include "e2e_util.h"
#include "plate_scenes.h"
#include "scenes/mesh_builders.h"

namespace sb::test {

using core::ImageF;
using core::make_area_light;
using core::Scene;

namespace {

using json = nlohmann::json;

// One plate whose straight edge runs along z at x = 0, at height 1 under the
// light at height kLightHeight: from a ground point at x it hides, of a
// segment along x, the light's x in [x + (x0 − x)·k, −x·(k − 1)], k = 3.
const Plate kPlate{-3.0f, 0.0f, -3.0f, 3.0f, 1.0f};
constexpr int kHeidrichMapSize = 1024;  // heidrich_linear's default

// The closed form at ground point (x, z) for a segment of length `length`
// along x (`along_x`) or along z, centred under the light.
double segment_visibility(double x, double z, double length, bool along_x) {
  const double k = kLightHeight / kPlate.h, half = 0.5 * length;
  const auto projected = [&](double lo, double hi, double at) {
    return std::pair<double, double>{at + (lo - at) * k, at + (hi - at) * k};
  };
  const auto [px0, px1] = projected(kPlate.x0, kPlate.x1, x);
  const auto [pz0, pz1] = projected(kPlate.z0, kPlate.z1, z);
  // The segment's points: (t, 0) along x or (0, t) along z, |t| <= half.
  const double other_lo = along_x ? pz0 : px0, other_hi = along_x ? pz1 : px1;
  if (!(other_lo <= 0.0 && 0.0 <= other_hi)) return 1.0;
  const double lo = along_x ? px0 : pz0, hi = along_x ? px1 : pz1;
  const double hidden = std::max(0.0, std::min(hi, half) - std::max(lo, -half));
  return 1.0 - hidden / length;
}

json experiment(const std::string& file, const json& size, const json& techniques) {
  json scene = plate_scene(file, 1.0);
  scene["light"]["size"] = size;
  return {{"name", "heidrich_linear"},
          {"scenes", json::array({scene})},
          {"techniques", techniques},
          {"resolutions", json::array({json::array({256, 192})})},
          {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"method", "exact"}}}};
}

// At its default map size, kHeidrichMapSize.
json heidrich() { return "heidrich_linear"; }

// World size of 2 texels of a map from the segment's end, on the ground
// (parallel to the map's image plane, kLightHeight below the end).
float two_texels_on_ground(float length, bool along_x) {
  Scene scene;
  scene.meshes.push_back(make_box("plate0", {-1.5f, kPlate.h, 0.0f}, {1.5f, 1e-4f, 3.0f}));
  scene.light = make_area_light({0.0f, kLightHeight, 0.0f}, glm::vec3(0.0f),
                                along_x ? 0.0f : length, along_x ? length : 0.0f);
  const techniques::LightFrustum f =
      techniques::fit_light_frustum(scene, scene.light.segment_end(0.0f));
  return 2.0f * f.texel_per_distance(kHeidrichMapSize) * kLightHeight;
}

struct Agreement {
  size_t compared = 0, penumbra = 0, over = 0;
  double worst = 0.0, worst_reference = 0.0, squares = 0.0;
  double rmse() const { return compared ? std::sqrt(squares / double(compared)) : 0.0; }
};

// Ground pixels under the plate's middle (|z| < 2, x > −2), more than
// `band` from the hard shadows' boundaries `edges`.
Agreement compare(const RunOutput& out, double length, bool along_x, float band,
                  const std::vector<double>& edges) {
  const ImageF positions = out.gbuffer_positions();
  const std::vector<bool> ground = ground_pixels(positions);
  const ImageF v = out.visibility("heidrich_linear");
  const ImageF reference = out.reference_visibility();
  Agreement a;
  for (size_t i = 0; i < ground.size(); ++i) {
    if (!ground[i]) continue;
    const double x = positions.data[i * 4], z = positions.data[i * 4 + 2];
    if (std::fabs(z) > 2.0 || x < -2.0) continue;
    bool near_edge = false;
    for (const double e : edges) near_edge = near_edge || std::fabs(x - e) < band;
    if (near_edge) continue;
    const double truth = segment_visibility(x, z, length, along_x);
    a.worst_reference = std::max(a.worst_reference, std::fabs(reference.data[i] - truth));
    const double error = std::fabs(v.data[i] - truth);
    ++a.compared;
    a.penumbra += truth > 0.0 && truth < 1.0;
    a.over += error > 0.05;
    a.worst = std::max(a.worst, error);
    a.squares += error * error;
  }
  return a;
}

TEST(HeidrichLinear, AcrossAnEdgeItIsWithinFiveHundredthsOfTheRampOutsideTwoTexels) {
  TempDir dir;
  const std::string file = write_plates(dir.path, {kPlate}, {0.6f, 3.2f, 2.4f});
  const double length = 1.0;
  const auto out = run_config(
      experiment(file, json::array({0.0, length}), json::array({heidrich(), "shadow_map"})),
      "heidrich_across", gl::Backend::OSMesa, true, /*write_gbuffer=*/true);
  ASSERT_EQ(out.summary.ok, 2) << out.records.at(0).value("reason", "");
  // make_area_light puts a [0, h] light's segment along x under a light
  // facing straight down: across the edge.
  const float band = two_texels_on_ground(float(length), /*along_x=*/true);
  // The hard shadows from the ends (x = ±½) begin at x = ∓½/(k − 1).
  const double k = kLightHeight / kPlate.h;
  const Agreement a =
      compare(out, length, true, band, {-0.5 * length / (k - 1.0), 0.5 * length / (k - 1.0)});
  std::printf(
      "band %.4f: %zu pixels, %zu in the penumbra, %zu over 0.05, worst %.4f "
      "(exact reference's worst %.2e)\n",
      double(band), a.compared, a.penumbra, a.over, a.worst, a.worst_reference);
  EXPECT_GT(a.penumbra, 800u);
  // Up to the boundaries too: the lookup fills the slivers no skin covers
  // beside them from the nearest skin, not with `lit`.
  const Agreement all = compare(out, length, true, 0.0f, {});
  std::printf("every ground pixel: RMSE %.4f, worst %.4f\n", all.rmse(), all.worst);
  EXPECT_LE(all.worst, 0.05);
  EXPECT_LT(a.worst_reference, 1e-4);  // the exact reference is the closed form
  EXPECT_LE(a.worst, 0.05);
  // A hard map knows no penumbra.
  const auto rmse = [&](const std::string& t) {
    return out.record(t)["metrics"]["visibility"]["all"]["rmse"].get<double>();
  };
  EXPECT_LT(rmse("heidrich_linear"), 0.5 * rmse("shadow_map"));
}

// The plates scene's edge under a segment across it, from the side (the
// light's ends both beyond the plate's far edge): a skin's ends are
// quantised to the other map's texels, and the slivers beside the edges
// that no skin covers take the nearest skin's shade, not `lit`, so the
// whole ground is within 0.05 of the exact reference, the hard shadows'
// boundaries included.
TEST(HeidrichLinear, TheSliversNoSkinCoversTakeTheNearestSkinsShade) {
  const json config = {
      {"name", "heidrich_linear"},
      {"scenes", json::array({{{"type", "plates"}, {"light", {{"size", json::array({0, 2})}}}}})},
      {"techniques", json::array({heidrich()})},
      {"resolutions", json::array({json::array({256, 192})})},
      {"frames", {{"warmup", 0}, {"timed", 1}}},
      {"reference", {{"method", "exact"}}}};
  const auto out =
      run_config(config, "heidrich_slivers", gl::Backend::OSMesa, true, /*write_gbuffer=*/true);
  ASSERT_EQ(out.summary.ok, 1) << out.records.at(0).value("reason", "");
  const std::vector<bool> ground = ground_pixels(out.gbuffer_positions());
  const ImageF v = out.visibility("heidrich_linear");
  const ImageF reference = out.reference_visibility();
  size_t n = 0, penumbra = 0;
  double worst = 0.0;
  for (size_t i = 0; i < ground.size(); ++i) {
    if (!ground[i]) continue;
    ++n;
    penumbra += reference.data[i] > 0.0f && reference.data[i] < 1.0f;
    worst = std::max(worst, double(std::fabs(v.data[i] - reference.data[i])));
  }
  std::printf("%zu ground pixels, %zu in the penumbra, worst %.4f\n", n, penumbra, worst);
  EXPECT_GT(penumbra, 3000u);
  EXPECT_LE(worst, 0.05);
}

TEST(HeidrichLinear, AlongAnEdgeTheShadowIsHard) {
  TempDir dir;
  const std::string file = write_plates(dir.path, {kPlate}, {0.6f, 3.2f, 2.4f});
  const double length = 1.0;
  const auto out =
      run_config(experiment(file, json::array({length, 0.0}), json::array({heidrich()})),
                 "heidrich_along", gl::Backend::OSMesa, true, /*write_gbuffer=*/true);
  ASSERT_EQ(out.summary.ok, 1) << out.records.at(0).value("reason", "");
  const float band = two_texels_on_ground(float(length), /*along_x=*/false);
  const Agreement a = compare(out, length, false, band, {0.0});
  std::printf("band %.4f: %zu pixels, %zu in the penumbra, %zu over 0.05, worst %.4f\n",
              double(band), a.compared, a.penumbra, a.over, a.worst);
  EXPECT_GT(a.compared, 5000u);
  EXPECT_EQ(a.penumbra, 0u);
  EXPECT_LT(a.worst_reference, 1e-4);
  EXPECT_LE(a.worst, 0.05);
}

TEST(HeidrichLinear, ARectangleOrAPointSkipsItAndASegmentSkipsTheRectangleTechniques) {
  TempDir dir;
  const std::string file = write_plates(dir.path, {kPlate}, {0.6f, 3.2f, 2.4f});
  const json techniques = json::array({heidrich(), "pcss", "penumbra_wedges", "smoothies",
                                       "plateaus", "occlusion_textures", "accumulation"});
  for (const json& size : {json(1.0), json(0.0), json::array({0.0, 1.0})}) {
    json config = experiment(file, size, techniques);
    config["reference"] = {{"spp", 4}};
    config["resolutions"] = json::array({json::array({64, 48})});
    const auto out = run_config(config, "heidrich_skips");
    const bool segment = size.is_array();
    const json& h = out.record("heidrich_linear");
    if (segment) {
      EXPECT_EQ(h["status"], "ok") << h.value("reason", "");
    } else {
      EXPECT_EQ(h["status"], "skipped");
      const std::string reason = h.value("reason", "");
      EXPECT_NE(reason.find("needs a linear light"), std::string::npos) << reason;
      EXPECT_NE(reason.find(size == json(0.0) ? "a point" : "a 1×1 rectangle"), std::string::npos)
          << reason;
    }
    for (const char* t :
         {"pcss", "penumbra_wedges", "smoothies", "plateaus", "occlusion_textures"}) {
      const json& r = out.record(t);
      if (segment) {
        EXPECT_EQ(r["status"], "skipped") << t;
        EXPECT_NE(r.value("reason", "")
                      .find("needs a rectangular light; the scene's light is a 0×1 "
                            "segment"),
                  std::string::npos)
            << t << ": " << r.value("reason", "");
      } else {
        EXPECT_EQ(r["status"], "ok") << t << ": " << r.value("reason", "");
      }
    }
    EXPECT_EQ(out.record("accumulation")["status"], "ok");
  }
}

}  // namespace
}  // namespace sb::test
