// planar and planar_soft (techniques/planar/): Blinn's projected shadows on
// the receiver plane, against the ray-traced reference and the shadow map,
// overlaps that darken once, and scenes they cannot run on.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../config/cli_runner.h"
#include "../gltf/gltf_builder.h"
#include "e2e_util.h"
#include "scenes/gltf_export.h"
#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"

namespace sb::test {

using core::ImageF;
using core::Scene;

namespace {

using json = nlohmann::json;

json experiment(const json& scenes, const json& techniques, int spp) {
  return {{"name", "planar"},
          {"scenes", scenes},
          {"techniques", techniques},
          {"resolutions", json::array({json::array({160, 120})})},
          {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"spp", spp}}}};
}

// Within `r` pixels of a shadow edge of `v` (its (2r+1)² window holds both
// V < ½ and V >= ½).
bool near_edge(const ImageF& v, int x, int y, int r) {
  bool dark = false, lit = false;
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx) {
      const int xx = x + dx, yy = y + dy;
      if (xx < 0 || yy < 0 || xx >= v.width || yy >= v.height) continue;
      (v.data[size_t(yy) * size_t(v.width) + size_t(xx)] < 0.5f ? dark : lit) = true;
    }
  return dark && lit;
}

struct Disagreement {
  size_t ground = 0;
  size_t differ = 0;           // |a − b| > ½
  size_t differ_off_edge = 0;  // of those, further than `r` pixels from an edge of `edges`
  double mean_abs = 0.0;
};

Disagreement disagreement(const ImageF& a, const ImageF& b, const std::vector<bool>& ground,
                          const ImageF& edges, int r) {
  Disagreement d;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const size_t i = size_t(y) * size_t(a.width) + size_t(x);
      if (!ground[i]) continue;
      ++d.ground;
      const double diff = std::abs(double(a.data[i]) - double(b.data[i]));
      d.mean_abs += diff;
      if (diff > 0.5) {
        ++d.differ;
        if (!near_edge(edges, x, y, r)) ++d.differ_off_edge;
      }
    }
  d.mean_abs /= double(std::max<size_t>(d.ground, 1));
  return d;
}

// For a light a thousandth of the scene, the reference is a hard shadow from
// the light's centre: planar must be it on the ground, and the shadow map may
// differ from it only along its aliased edges.
TEST(Planar, EqualsTheReferenceAndTheShadowMapOnTheGroundForATinyLight) {
  const auto out = run_config(
      experiment(
          json::array({small_scene(1e-3)}),
          json::array({"planar", json{{"name", "shadow_map"}, {"params", {{"size", 2048}}}}}), 16),
      "planar_tiny_light", gl::Backend::OSMesa, true, /*write_gbuffer=*/true);
  ASSERT_EQ(out.summary.failed, 0);
  ASSERT_EQ(out.summary.skipped, 0);
  const std::vector<bool> ground = ground_pixels(out.gbuffer_positions());
  const ImageF planar = out.visibility("planar");
  const ImageF ref = out.reference_visibility();
  const ImageF sm = out.visibility("shadow_map/size=2048");

  const Disagreement vs_ref = disagreement(planar, ref, ground, ref, 1);
  const Disagreement vs_sm = disagreement(planar, sm, ground, planar, 2);
  std::printf(
      "ground %zu px; planar vs reference: %zu differ (%zu off edges), MAE %.5f; "
      "vs shadow_map: %zu differ (%zu off edges)\n",
      vs_ref.ground, vs_ref.differ, vs_ref.differ_off_edge, vs_ref.mean_abs, vs_sm.differ,
      vs_sm.differ_off_edge);
  ASSERT_GT(vs_ref.ground, 160u * 120u / 3);
  // The shadow is there: a tenth of the ground or more is dark.
  size_t dark = 0;
  for (size_t i = 0; i < ground.size(); ++i) dark += ground[i] && planar.data[i] < 0.5f;
  EXPECT_GT(dark, vs_ref.ground / 10);
  // Against the truth: only pixels whose centre falls in the thin penumbra
  // may differ, and they sit on the edge.
  EXPECT_EQ(vs_ref.differ_off_edge, 0u);
  EXPECT_LT(double(vs_ref.differ), 0.002 * double(vs_ref.ground));
  EXPECT_LT(vs_ref.mean_abs, 0.002);
  // Against the shadow map: its texels and bias move the edge by a pixel or two.
  EXPECT_EQ(vs_sm.differ_off_edge, 0u);
  EXPECT_LT(double(vs_sm.differ), 0.02 * double(vs_sm.ground));
}

// RMSE of V against the reference over the ground's penumbra (0 < V_ref < 1).
double ground_penumbra_rmse(const ImageF& v, const ImageF& ref, const std::vector<bool>& ground) {
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < ground.size(); ++i)
    if (ground[i] && ref.data[i] > 0.01f && ref.data[i] < 0.99f) {
      const double d = double(v.data[i]) - double(ref.data[i]);
      sum += d * d;
      ++n;
    }
  EXPECT_GT(n, 500u);
  return std::sqrt(sum / double(std::max<size_t>(n, 1)));
}

// planar_soft converges to the reference's penumbra on the ground as light
// points are added. Averaged over four seeds, so no single seed's luck decides.
TEST(Planar, SoftPenumbraErrorIsSmallAndFallsWithSamples) {
  const json seeds = json::array({1, 2, 3, 4});
  const auto out = run_config(
      experiment(
          json::array({small_scene(1.5)}),
          json::array({json{{"name", "planar_soft"},
                            {"params", {{"samples", json::array({16, 64})}, {"seed", seeds}}}}}),
          1024),
      "planar_soft_penumbra", gl::Backend::OSMesa, true, /*write_gbuffer=*/true);
  ASSERT_EQ(out.summary.failed, 0);
  const std::vector<bool> ground = ground_pixels(out.gbuffer_positions());
  const ImageF ref = out.reference_visibility();
  const auto mean_rmse = [&](int samples) {
    double sum = 0.0;
    for (const auto& seed : seeds) {
      const std::string variant = "planar_soft/samples=" + std::to_string(samples) +
                                  ",seed=" + std::to_string(seed.get<int>());
      sum += ground_penumbra_rmse(out.visibility(variant), ref, ground);
    }
    return sum / double(seeds.size());
  };
  const double rmse16 = mean_rmse(16), rmse64 = mean_rmse(64);
  std::printf("ground penumbra RMSE: 16 samples %.4f, 64 samples %.4f\n", rmse16, rmse64);
  EXPECT_LT(rmse64, 0.03);
  // Stratified sampling: error falls about as N^-0.75, a factor 2.8 here.
  EXPECT_LT(rmse64, 0.6 * rmse16);
}

// The stacked plates' shadows overlap on the ground (the upper plate's falls
// in the lower one's umbra), and so do the flattened faces of one caster
// (light-facing ones meet along shared edges; an open caster's back faces
// cover its front faces'): each light point darkens a pixel once, so V takes
// only the values k/N, down to exactly 0. Without the stencil the harness
// fails these jobs (V = -1 on the overlap).
TEST(Planar, OverlappingCastersDarkenOnce) {
  const json scenes = json::array(
      {small_scene(1.0), json{{"type", "plates"}, {"params", {{"layout", "stacked"}}}}});
  const auto out = run_config(
      experiment(
          scenes,
          json::array({"planar", json{{"name", "planar_soft"}, {"params", {{"samples", 16}}}}}), 4),
      "planar_overlap");
  ASSERT_EQ(out.summary.failed, 0);
  ASSERT_EQ(out.records.size(), 4u);
  for (const auto& r : out.records) {
    const std::string variant = r["technique_variant"];
    SCOPED_TRACE(r["job_id"].get<std::string>());
    ASSERT_EQ(r["status"], "ok") << r.value("reason", "");
    const ImageF v = out.image(r, "visibility");
    const float n = variant == "planar" ? 1.0f : 16.0f;
    size_t zero = 0, off_grid = 0;
    for (float x : v.data) {
      EXPECT_GE(x, 0.0f);
      EXPECT_LE(x, 1.0f);
      zero += x == 0.0f;
      off_grid += std::abs(x * n - std::round(x * n)) > 1e-4f;
    }
    EXPECT_EQ(off_grid, 0u) << "V is not a multiple of 1/" << n;
    EXPECT_GT(zero, v.pixel_count() / 100) << "no umbra";
  }
}

// A pillar reaching above a low light, and a sphere: the pillar's part above
// the light's height cannot shadow the ground, and projected it would land
// on the far side of infinity (an anti-shadow); the part below casts a
// shadow that runs off to infinity. planar clips at the light's height.
std::string write_pillar_above_the_light(const std::filesystem::path& dir) {
  Scene s;
  s.meshes.push_back(make_ground_plane("ground", {0.0f, 0.0f, 0.0f}, 30.0f));
  s.meshes.push_back(make_box("pillar", {1.5f, 2.5f, 0.0f}, {0.3f, 2.5f, 0.3f}));
  s.meshes.push_back(make_uv_sphere("ball", {3.0f, 0.8f, 2.0f}, 0.6f, 16, 12));
  s.light.center = {0.0f, 3.0f, 0.0f};
  s.light.target = {0.0f, 0.0f, 0.0f};
  // The anti-shadow would fall on the ground at x < -2.25, partly behind
  // this camera, where the camera's own clipping (w > 0) does not remove it.
  s.camera.eye = {-5.0f, 5.0f, 1.0f};
  s.camera.target = {2.0f, 0.0f, 0.0f};
  const auto file = dir / "pillar.glb";
  export_glb(s, file.string());
  return file.string();
}

TEST(Planar, CastersAboveTheLightCastNoAntiShadow) {
  TempDir dir;
  const json scene = {
      {"type", "gltf"},
      {"params", {{"file", write_pillar_above_the_light(dir.path)}}},
      {"light", {{"center", {0.0, 3.0, 0.0}}, {"target", {0, 0, 0}}, {"size", 1e-3}}}};
  const auto out = run_config(experiment(json::array({scene}), json::array({"planar"}), 16),
                              "planar_anti_shadow", gl::Backend::OSMesa, true,
                              /*write_gbuffer=*/true);
  ASSERT_EQ(out.summary.ok, 1) << out.records.at(0).value("reason", "");
  const std::vector<bool> ground = ground_pixels(out.gbuffer_positions());
  const ImageF planar = out.visibility("planar");
  const ImageF ref = out.reference_visibility();
  const Disagreement d = disagreement(planar, ref, ground, ref, 1);
  size_t dark = 0;
  for (size_t i = 0; i < ground.size(); ++i) dark += ground[i] && ref.data[i] < 0.5f;
  std::printf("ground %zu px, %zu in shadow; planar vs reference: %zu differ (%zu off edges)\n",
              d.ground, dark, d.differ, d.differ_off_edge);
  ASSERT_GT(d.ground, 160u * 120u / 3);
  EXPECT_GT(dark, d.ground / 20);
  EXPECT_EQ(d.differ_off_edge, 0u);
  EXPECT_LT(double(d.differ), 0.002 * double(d.ground));
}

// Two spheres and nothing under them: no planar receiver. The foliage has
// none either (the planner finds no plane with every caster vertex on its
// light side), so its alpha-tested leaves are never the reason.
std::string write_spheres_without_ground(const std::filesystem::path& dir) {
  Scene s;
  s.meshes.push_back(make_uv_sphere("a", {-1.0f, 0.0f, 0.0f}, 0.6f, 12, 8));
  s.meshes.push_back(make_uv_sphere("b", {1.0f, 0.5f, 0.0f}, 0.6f, 12, 8));
  s.light.center = {0.0f, 6.0f, 0.0f};
  s.light.target = {0.0f, 0.0f, 0.0f};
  s.camera.eye = {0.0f, 1.0f, 5.0f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  const auto file = dir / "spheres.glb";
  export_glb(s, file.string());
  return file.string();
}

TEST(Planar, SkipsScenesWithoutAPlanarReceiver) {
  TempDir dir;
  const json config = {
      {"name", "planar_skip"},
      {"scenes", json::array({{{"type", "gltf"},
                               {"params", {{"file", write_spheres_without_ground(dir.path)}}}},
                              {{"type", "foliage"}, {"params", {{"trees", 1}, {"depth", 2}}}}})},
      {"techniques", json::array({"none", "planar", "planar_soft", "plateaus"})},
      {"resolutions", json::array({json::array({48, 32})})},
      {"frames", {{"warmup", 0}, {"timed", 1}}},
      {"reference", {{"spp", 4}, {"cache", false}}}};
  const auto out = run_config(config, "planar_skip");
  ASSERT_EQ(out.records.size(), 8u);
  EXPECT_EQ(out.summary.ok, 2);
  EXPECT_EQ(out.summary.skipped, 6);
  for (const auto& r : out.records) {
    SCOPED_TRACE(r["job_id"].get<std::string>());
    const std::string technique = r["technique_variant"];
    if (technique == "none") {
      EXPECT_EQ(r["status"], "ok");
      continue;
    }
    EXPECT_EQ(r["status"], "skipped");
    EXPECT_EQ(r.value("reason", ""),
              technique + " needs a planar receiver under every caster; the scene has none")
        << r.dump(2).substr(0, 2000);
  }

  // `shadowbench plan` says the same before anything runs.
  const std::string file = dir / "planar_skip.json";
  std::ofstream(file) << config.dump();
  const auto plan = run_cli("plan " + file);
  EXPECT_EQ(plan.exit_code, 0) << plan.output;
  EXPECT_NE(plan.output.find("planar needs a planar receiver under every caster"),
            std::string::npos)
      << plan.output;
  EXPECT_NE(plan.output.find("planar_soft needs a planar receiver under every caster"),
            std::string::npos)
      << plan.output;
}

}  // namespace
}  // namespace sb::test
