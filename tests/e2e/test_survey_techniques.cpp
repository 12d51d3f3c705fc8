// The survey techniques of Shypula 2008 and Rahman 2007 (docs/
// survey_techniques.md): blurred_visibility, plateaus, penumbra_maps and
// smoothies, against closed forms on the plates edge, the `standing`
// scene's foot and far end, and the cases that could give NaN.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "e2e_util.h"
#include "metrics/shadow_classes.h"

namespace sb::test {

using core::ImageF;

namespace {

using json = nlohmann::json;

json experiment(const json& scenes, const json& techniques, int width, int height, int spp) {
  return {{"name", "survey"},
          {"scenes", scenes},
          {"techniques", techniques},
          {"resolutions", json::array({json::array({width, height})})},
          {"frames", {{"warmup", 0}, {"timed", 1}}},
          {"reference", {{"spp", spp}}}};
}

struct GroundPixel {
  float x, z, v;  // world x and z, the visibility
};

// The ground pixels (y = 0) of one row of `positions`, with V from `v`.
std::vector<GroundPixel> ground_row(const ImageF& positions, const ImageF& v, int row) {
  std::vector<GroundPixel> out;
  for (int x = 0; x < v.width; ++x) {
    const size_t i = size_t(row) * size_t(v.width) + size_t(x);
    const float* p = &positions.data[i * 4];
    if (p[3] != 0.0f && std::abs(p[1]) < 1e-4f) out.push_back({p[0], p[2], v.data[i]});
  }
  return out;
}

// plates "edge" at light size L: the plate's top edge at e = height +
// thickness / 2 runs along z at x = 0, the light's centre at x = −d (d =
// max(3, L)) and height H (scenes/plates.cpp). From the light's centre the
// edge's shadow falls at x_h = d·k, k = e / (H − e); the light's far side
// (x = −d − L/2) sees past it up to x_o = (d + L/2)·k, the outer boundary.
// An outer-penumbra technique must keep its hard shadow up to x_h (V = 0
// before it: no inner penumbra) and be lit from x_o on, with its first lit
// pixel at x_h and its last dark one at x_o, each within two pixels.
TEST(SurveyTechniques, OuterPenumbraOfAStraightEdgeRunsFromTheHardEdgeToTheAnalyticBoundary) {
  const double light_size = 1.5;
  const json scene = {{"type", "plates"}, {"params", {{"light_size", light_size}}}};
  const json techniques = json::array(
      {"plateaus", json{{"name", "penumbra_maps"}, {"params", {{"size", 2048}}}},
       json{{"name", "smoothies"}, {"params", {{"size", 2048}, {"width_texels", 128}}}}});
  const auto out = run_config(experiment(json::array({scene}), techniques, 320, 240, 4),
                              "survey_plates_edge", gl::Backend::OSMesa, true,
                              /*write_gbuffer=*/true);
  ASSERT_EQ(out.summary.failed, 0);
  ASSERT_EQ(out.summary.skipped, 0);
  const ImageF positions = out.gbuffer_positions();
  const double e = 1.0 + 0.025, k = e / (8.0 - e), d = std::max(3.0, light_size);
  const double hard = d * k, outer = (d + 0.5 * light_size) * k;
  for (const std::string variant :
       {"plateaus", "penumbra_maps/size=2048", "smoothies/width_texels=128,size=2048"}) {
    SCOPED_TRACE(variant);
    const ImageF v = out.visibility(variant);
    int rows = 0;
    double worst_inner = 0.0, worst_outer = 0.0;
    for (int row = 0; row < v.height; row += 4) {
      const std::vector<GroundPixel> g = ground_row(positions, v, row);
      if (g.size() < 20) continue;
      double first_lit = 1e9, last_dark = -1e9, pixel = 0.0;
      for (size_t i = 0; i < g.size(); ++i) {
        if (i + 1 < g.size()) pixel = std::max(pixel, double(std::abs(g[i + 1].x - g[i].x)));
        if (g[i].v > 1e-4f) first_lit = std::min(first_lit, double(g[i].x));
        if (g[i].v < 1.0f - 1e-4f) last_dark = std::max(last_dark, double(g[i].x));
        ASSERT_TRUE(std::isfinite(g[i].v));
      }
      ++rows;
      EXPECT_NEAR(first_lit, hard, 2.0 * pixel) << "row " << row;
      EXPECT_NEAR(last_dark, outer, 2.0 * pixel) << "row " << row;
      worst_inner = std::max(worst_inner, std::abs(first_lit - hard) / pixel);
      worst_outer = std::max(worst_outer, std::abs(last_dark - outer) / pixel);
    }
    EXPECT_GT(rows, 40);
    std::printf("%s: hard edge within %.2f px, outer boundary within %.2f px (%d rows)\n",
                variant.c_str(), worst_inner, worst_outer, rows);
  }
}

// The mean over ground pixels with world x in [lo, hi]: soft pixels
// (0.02 < V < 0.98) per pixel of the strip, and the RMSE against `ref`.
struct Strip {
  double softness = 0.0, rmse = 0.0;
  size_t pixels = 0;
};

Strip strip(const ImageF& positions, const ImageF& v, const ImageF& ref, float lo, float hi) {
  Strip s;
  size_t soft = 0;
  double sum = 0.0;
  for (size_t i = 0; i < v.pixel_count(); ++i) {
    const float* p = &positions.data[i * 4];
    if (p[3] == 0.0f || std::abs(p[1]) >= 1e-4f || p[0] < lo || p[0] > hi) continue;
    ++s.pixels;
    soft += v.data[i] > 0.02f && v.data[i] < 0.98f;
    const double diff = double(v.data[i]) - double(ref.data[i]);
    sum += diff * diff;
  }
  s.softness = double(soft) / double(std::max<size_t>(s.pixels, 1));
  s.rmse = std::sqrt(sum / double(std::max<size_t>(s.pixels, 1)));
  return s;
}

// The standing box's shadow is hard at its foot and widest at its far end.
// A fixed-width blur gives both ends the same softness; the techniques that
// scale the penumbra by the occluder's distance follow the truth. The
// errors at either end are printed for docs/survey_techniques.md.
TEST(SurveyTechniques, BlurredVisibilityIsAsSoftAtTheFootAsAtTheFarEndWhereTheTruthIsNot) {
  const json scene = {{"type", "standing"}};
  const json techniques =
      json::array({json{{"name", "blurred_visibility"}, {"params", {{"radius", 4}}}},
                   json{{"name", "blurred_visibility"},
                        {"params", {{"space", "light"}, {"size", 512}, {"radius", 6}}}},
                   "plateaus", "penumbra_maps"});
  const auto out = run_config(experiment(json::array({scene}), techniques, 320, 240, 256),
                              "survey_standing", gl::Backend::OSMesa, true, /*write_gbuffer=*/true);
  ASSERT_EQ(out.summary.failed, 0);
  ASSERT_EQ(out.summary.skipped, 0);
  const ImageF positions = out.gbuffer_positions();
  const ImageF ref = out.reference_visibility();
  // The box's foot is at x = 0.2 and the shadow's tip at 1.8 (standing.cpp).
  const auto near = [&](const ImageF& v) { return strip(positions, v, ref, 0.2f, 0.45f); };
  const auto far = [&](const ImageF& v) { return strip(positions, v, ref, 1.45f, 1.8f); };
  const Strip ref_near = near(ref), ref_far = far(ref);
  std::printf("reference: soft share %.3f near the foot, %.3f at the far end\n", ref_near.softness,
              ref_far.softness);
  ASSERT_GT(ref_near.pixels, 300u);
  ASSERT_GT(ref_far.pixels, 300u);
  EXPECT_GT(ref_far.softness, 2.5 * ref_near.softness);

  // Both ends of each technique's shadow, printed for docs/survey_techniques.md.
  const auto ends = [&](const std::string& variant) {
    const ImageF v = out.visibility(variant);
    const std::pair<Strip, Strip> nf{near(v), far(v)};
    std::printf("%s: soft share %.3f near, %.3f far; RMSE %.4f near, %.4f far\n", variant.c_str(),
                nf.first.softness, nf.second.softness, nf.first.rmse, nf.second.rmse);
    return nf;
  };
  for (const std::string variant :
       {"blurred_visibility/radius=4", "blurred_visibility/space=light,radius=6,size=512"}) {
    SCOPED_TRACE(variant);
    const auto [n, f] = ends(variant);
    // The same softness at both ends, within the perspective's difference.
    EXPECT_LT(f.softness, 1.6 * n.softness);
    EXPECT_GT(f.softness, n.softness / 1.6);
  }
  for (const std::string variant : {"plateaus", "penumbra_maps"}) {
    SCOPED_TRACE(variant);
    const auto [n, f] = ends(variant);
    // Their outer halves only: measured 2.1 times softer at the far end.
    EXPECT_GT(f.softness, 1.8 * n.softness);
  }
}

// Cases that could divide by zero: a light much larger than the caster, an
// occluder standing on its receiver (zero penumbra at the contact), and a
// light of no size (no penumbra at all, where the band techniques must
// give the hard shadow, and two_map_bound's apexes meet at the light).
// Every job is ok and every V finite in [0, 1].
TEST(SurveyTechniques, HugeLightsContactAndNoPenumbraStayFinite) {
  const json scenes = json::array({json{{"type", "standing"}, {"params", {{"light_size", 8.0}}}},
                                   json{{"type", "standing"}, {"params", {{"light_size", 0.0}}}}});
  const json techniques = json::array(
      {"blurred_visibility", json{{"name", "blurred_visibility"}, {"params", {{"space", "light"}}}},
       "plateaus", "penumbra_maps", "smoothies", "planar"});
  const auto out = run_config(experiment(scenes, techniques, 96, 72, 4), "survey_extremes");
  ASSERT_EQ(out.records.size(), 12u);
  ImageF planar_hard;
  for (const auto& r : out.records) {
    SCOPED_TRACE(r["job_id"].get<std::string>());
    ASSERT_EQ(r["status"], "ok") << r.value("reason", "");
    const ImageF v = out.image(r, "visibility");
    for (float x : v.data) {
      ASSERT_TRUE(std::isfinite(x));
      ASSERT_GE(x, 0.0f);
      ASSERT_LE(x, 1.0f);
    }
    if (r["technique_variant"] == "planar" && r["scene"]["params"]["light_size"] == 0.0)
      planar_hard = v;
  }
  ASSERT_GT(planar_hard.pixel_count(), 0u);
  // With a point light, plateaus is the hard planar shadow, pixel for pixel.
  for (const auto& r : out.records) {
    if (r["technique_variant"] != "plateaus" || r["scene"]["params"]["light_size"] != 0.0) continue;
    const ImageF v = out.image(r, "visibility");
    size_t differ = 0;
    for (size_t i = 0; i < v.data.size(); ++i) differ += v.data[i] != planar_hard.data[i];
    EXPECT_EQ(differ, 0u);
  }
}

// two_map_bound on the plates edge: where the reference is lit or umbra
// with no other class within two pixels, the two maps must classify the
// pixel the same (Shypula's bound holds for an occluder as wide as the
// extent). The search shading keeps every penumbra pixel strictly inside
// (0, 1), and so does the gradient's, so the record's classes are the
// classification's; both shadings beat V = ½ in the penumbra.
TEST(SurveyTechniques, TwoMapBoundClassifiesLitAndUmbraAwayFromClassBordersOnThePlates) {
  const json scene = {{"type", "plates"}, {"params", {{"light_size", 1.5}}}};
  const json techniques = json::array({json{
      {"name", "two_map_bound"}, {"params", {{"shade", {"midpoint", "search", "gradient"}}}}}});
  const auto out = run_config(experiment(json::array({scene}), techniques, 320, 240, 256),
                              "survey_two_map_plates");
  ASSERT_EQ(out.summary.failed, 0);
  const ImageF ref = out.reference_visibility();
  const ImageF midpoint = out.visibility("two_map_bound/shade=midpoint");
  const ImageF search = out.visibility("two_map_bound/shade=search");
  const ImageF gradient = out.visibility("two_map_bound/shade=gradient");
  using metrics::shadow_class;
  using metrics::ShadowClass;
  const auto ref_class = [&](int x, int y) {
    return shadow_class(ref.data[size_t(y) * size_t(ref.width) + size_t(x)]);
  };
  size_t checked = 0, differ = 0, penumbra = 0;
  for (int y = 2; y < ref.height - 2; ++y)
    for (int x = 2; x < ref.width - 2; ++x) {
      const size_t i = size_t(y) * size_t(ref.width) + size_t(x);
      // The two shadings classify alike, and the search's penumbra stays inside (0, 1).
      ASSERT_EQ(shadow_class(midpoint.data[i]), shadow_class(search.data[i])) << x << "," << y;
      ASSERT_EQ(shadow_class(midpoint.data[i]), shadow_class(gradient.data[i])) << x << "," << y;
      if (shadow_class(midpoint.data[i]) == ShadowClass::Penumbra) {
        ++penumbra;
        EXPECT_EQ(midpoint.data[i], 0.5f);
      }
      const ShadowClass c = ref_class(x, y);
      if (c == ShadowClass::Penumbra) continue;
      bool interior = true;
      for (int dy = -2; dy <= 2 && interior; ++dy)
        for (int dx = -2; dx <= 2 && interior; ++dx) interior = ref_class(x + dx, y + dy) == c;
      if (!interior) continue;
      ++checked;
      differ += shadow_class(midpoint.data[i]) != c;
    }
  const json& classes = out.record("two_map_bound/shade=search")["classes"];
  std::printf(
      "%zu lit or umbra pixels away from borders, %zu classified otherwise; %zu penumbra; "
      "record: %s\n",
      checked, differ, penumbra, classes.dump().c_str());
  EXPECT_GT(checked, size_t(ref.pixel_count() / 2));
  EXPECT_GT(penumbra, 1000u);
  EXPECT_EQ(differ, 0u);
  // The record counts the same classes for every shading.
  EXPECT_EQ(classes["counts"], out.record("two_map_bound/shade=midpoint")["classes"]["counts"]);
  EXPECT_EQ(classes["counts"], out.record("two_map_bound/shade=gradient")["classes"]["counts"]);
  // Shading the penumbra beats the classification alone there: measured
  // penumbra RMSE 0.116 (search) and 0.039 (gradient) against 0.286 (½).
  const auto penumbra_rmse = [&](const std::string& variant) {
    return out.record(variant)["metrics"]["visibility"]["penumbra"]["rmse"].get<double>();
  };
  const double half = penumbra_rmse("two_map_bound/shade=midpoint");
  EXPECT_LT(penumbra_rmse("two_map_bound/shade=search"), 0.6 * half);
  EXPECT_LT(penumbra_rmse("two_map_bound/shade=gradient"), 0.25 * half);
}

}  // namespace
}  // namespace sb::test
