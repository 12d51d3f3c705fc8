// The V ramp of the outer-penumbra techniques (penumbra_maps, smoothies;
// plateaus, their planar cousin) across a straight edge, against the closed
// form of the truth and the exact reference, not only where it starts and
// ends (test_survey_techniques.cpp checks the boundaries).
//
// The truth. plates "edge" at light size L (scenes/plates.cpp): the plate's
// top edge at height e = height + thickness / 2 runs along z at x = 0; the
// square light, facing down, is centred at x = −d (d = max(3, L)) and height
// H. The ray from a ground point (x, 0, z), x > 0, to a light point of
// abscissa q meets the plate (its least x in the slab is at its top, where
// it is x + (q − x)·e/H) iff q ≤ −x/k, k = e / (H − e); the plate is wider
// than any such ray reaches in z. So V is the light's share beyond −x/k:
//   V(x) = clamp((x − x_i) / (x_o − x_i), 0, 1),
// linear from x_i = (d − L/2)·k to x_o = (d + L/2)·k, ½ at the hard edge
// x_h = d·k. The exact reference must agree to Clipper's precision.
//
// What the papers compute (docs/survey_techniques.md): the hard shadow from
// the light's centre is kept as the umbra, and the lit side of the hard edge
// is darkened from V = 0 at x_h to V = 1 at the outer boundary x_o, linearly
// in the light's image plane (Wyman & Hansen's penumbra map; Chan & Durand's
// smoothie α rescaled by the blocker and receiver depths; Haines' plateaus on
// the receiver plane). Here the ground is parallel to the map's image plane
// and the edge at one depth, so the ramp is linear in x:
//   R(x) = clamp((x − x_h) / (x_o − x_h), 0, 1) = max(0, 2·V(x) − 1).
// Its error against the truth is −min(V, 1 − V): −½ at x_h, 0 at x_i and
// x_o. Over the true penumbra, where V is uniform in [0, 1], the RMSE is
// 1/√12 = 0.2887 and the mean error −¼: the approximation's own error, which
// a faithful implementation must show, no less and no more.
//
// The tolerance. penumbra_maps and smoothies evaluate the ramp at the
// centres of the map's texels and look it up without filtering, so a pixel
// reads R at a point up to half a texel away in x: |V − R| ≤ R′·texel/2,
// R′ = 1/(x_o − x_h), the texel's size on the ground from the fitted
// frustum (measured 0.0192 of the bound's 0.0202). plateaus computes R at the
// pixel's own point (measured error 0). The bound on |V − R| is what tells
// a broken ramp: a constant ½ over the band keeps both boundaries and even
// the RMSE and mean error against the truth (0.2886, −0.25), but misses R
// by ½; a smoothstep misses it by 0.115 (both tried in a copy).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/light_frustum.h"
#include "core/scene_types.h"
#include "e2e_util.h"

namespace sb::test {

using core::find_scene_type;
using core::ImageF;
using core::Mesh;
using core::resolve_params;
using core::Scene;
using core::SceneType;

namespace {

using json = nlohmann::json;

constexpr double kLightSize = 1.5;
constexpr int kMapSize = 2048;

// The truth's closed form and the papers' ramp on the plates edge (above).
struct EdgePenumbra {
  double inner, hard, outer;  // x_i, x_h, x_o
  double truth(double x) const { return std::clamp((x - inner) / (outer - inner), 0.0, 1.0); }
  double ramp(double x) const { return std::clamp((x - hard) / (outer - hard), 0.0, 1.0); }
};

EdgePenumbra edge_penumbra(const Scene& plates) {
  const Mesh& plate = plates.meshes.front();
  float top = -1e30f;
  for (const glm::vec3& p : plate.positions) top = std::max(top, p.y);
  const double e = top, big_h = plates.light.center.y, d = -plates.light.center.x;
  const double k = e / (big_h - e), half = 0.5 * double(plates.light.width());
  return {(d - half) * k, d * k, (d + half) * k};
}

TEST(OuterPenumbraRamp, TechniquesDrawThePapersRampAndMissTheTruthByItsClosedFormError) {
  const SceneType* type = find_scene_type("plates");
  const Scene plates =
      type->build(resolve_params(type->params, {{"light_size", kLightSize}}, "", ""));
  ASSERT_EQ(plates.meshes.front().name, "plate");
  const EdgePenumbra edge = edge_penumbra(plates);
  // The map's texel on the ground (depth H below the light, along its axis).
  const techniques::LightFrustum frustum =
      techniques::fit_light_frustum(plates, plates.light.center);
  const double texel = double(frustum.texel_per_distance(kMapSize)) * plates.light.center.y;
  const double slope = 1.0 / (edge.outer - edge.hard);

  const json config = {
      {"name", "outer_penumbra_ramp"},
      {"scenes", {{{"type", "plates"}, {"params", {{"light_size", kLightSize}}}}}},
      {"techniques",
       {"plateaus",
        {{"name", "penumbra_maps"}, {"params", {{"size", kMapSize}}}},
        {{"name", "smoothies"}, {"params", {{"size", kMapSize}, {"width_texels", 128}}}}}},
      {"resolutions", {{320, 240}}},
      {"frames", {{"warmup", 0}, {"timed", 1}}},
      {"reference", {{"method", "exact"}}}};
  const auto out =
      run_config(config, "outer_penumbra_ramp", gl::Backend::OSMesa, true, /*write_gbuffer=*/true);
  ASSERT_EQ(out.summary.failed, 0);
  ASSERT_EQ(out.summary.skipped, 0);
  ASSERT_EQ(out.record("plateaus")["reference"]["method"], "exact_clipper");
  const ImageF positions = out.gbuffer_positions();
  const ImageF reference = out.reference_visibility();
  std::vector<size_t> ground;
  for (size_t i = 0; i < positions.pixel_count(); ++i) {
    const float* p = &positions.data[i * 4];
    if (p[3] != 0.0f && std::abs(p[1]) < 1e-4f) ground.push_back(i);
  }
  ASSERT_GT(ground.size(), positions.pixel_count() / 2);

  // The closed form is the truth: the exact reference agrees with it.
  double reference_worst = 0.0;
  for (size_t i : ground)
    reference_worst =
        std::max(reference_worst, std::abs(reference.data[i] - edge.truth(positions.data[i * 4])));
  std::printf("exact reference against the closed form: within %.2g\n", reference_worst);
  EXPECT_LT(reference_worst, 1e-3);

  struct Expected {
    std::string variant;
    double tolerance;
  };
  const double lookup = 0.5 * slope * texel + 1e-3;  // half a texel of the ramp, plus rounding
  for (const auto& [variant, tolerance] :
       {Expected{"plateaus", 1e-3}, Expected{"penumbra_maps/size=2048", lookup},
        Expected{"smoothies/width_texels=128,size=2048", lookup}}) {
    SCOPED_TRACE(variant);
    const ImageF v = out.visibility(variant);
    double worst = 0.0, ramp_sum = 0.0, truth_sum = 0.0, truth_signed = 0.0;
    size_t on_ramp = 0, in_penumbra = 0;
    for (size_t i : ground) {
      const double x = positions.data[i * 4], got = v.data[i];
      // Everywhere on the ground: V = 0 in the hard shadow, the ramp across
      // the outer penumbra, 1 beyond it.
      const double miss = got - edge.ramp(x);
      worst = std::max(worst, std::abs(miss));
      if (edge.ramp(x) > 0.0 && edge.ramp(x) < 1.0) {
        ++on_ramp;
        ramp_sum += miss * miss;
      }
      if (x > edge.inner && x < edge.outer) {
        ++in_penumbra;
        const double error = got - reference.data[i];
        truth_sum += error * error;
        truth_signed += error;
      }
    }
    ASSERT_GT(on_ramp, 2000u);
    const double ramp_rms = std::sqrt(ramp_sum / double(on_ramp));
    const double truth_rmse = std::sqrt(truth_sum / double(in_penumbra));
    const double truth_mean = truth_signed / double(in_penumbra);
    std::printf(
        "%s: |V − ramp| at most %.4f (bound %.4f), RMS %.4f over %zu ramp pixels; against the "
        "exact reference over %zu penumbra pixels RMSE %.4f, mean %.4f\n",
        variant.c_str(), worst, tolerance, ramp_rms, on_ramp, in_penumbra, truth_rmse, truth_mean);
    EXPECT_LE(worst, tolerance);
    // The approximation's error against the truth, 1/√12 and −¼ (above),
    // give or take the lookup's (RMS at most the tolerance / √3) and the
    // pixels' uneven spacing in x.
    EXPECT_NEAR(truth_rmse, 1.0 / std::sqrt(12.0), 0.005);
    EXPECT_NEAR(truth_mean, -0.25, 0.005);
  }
}

}  // namespace
}  // namespace sb::test
