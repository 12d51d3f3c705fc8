// The exact reference against the Monte Carlo one (256 spp) on the sphere
// grid, a jeep and a glTF file, at G-buffers made by primary rays: on at
// least 99.9% of the covered pixels they differ by at most four of the
// Monte Carlo reference's standard errors. σ (reference.h) is 0 where the
// samples all agree, which happens in a penumbra thinner than a stratum
// (exact 0.9993, sampled 1); there the error is taken as one sample's
// weight, 1/spp, the estimate's resolution.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "../common/scene_of_type.h"
#include "reference/reference.h"

namespace {

void expect_agreement(const sb::core::Scene& scene, const std::string& label) {
  const sb::reference::GBuffer g = sb::reference::trace_gbuffer(scene, 160, 120);
  sb::reference::Settings exact_settings;
  exact_settings.exact = true;
  const sb::reference::Result exact =
      sb::reference::compute(scene, g.positions, g.normals, exact_settings);
  ASSERT_EQ(exact.method, "exact_clipper") << exact.exact_fallback;
  const sb::reference::Result mc = sb::reference::compute(scene, g.positions, g.normals, {256, 1});
  size_t covered = 0, outside = 0, penumbra = 0;
  double worst = 0.0;
  for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
    if (!(g.positions.data[i * 4 + 3] > 0.5f)) continue;
    ++covered;
    const double d = std::abs(double(exact.visibility.data[i]) - double(mc.visibility.data[i]));
    penumbra += exact.visibility.data[i] > 0.0f && exact.visibility.data[i] < 1.0f;
    worst = std::max(worst, d);
    outside += d > 4.0 * std::max(double(mc.std_error.data[i]), 1.0 / 256.0);
  }
  std::printf(
      "%s: %zu covered px (%zu in the exact penumbra), %zu beyond 4 sigma, max |diff| %.4f\n",
      label.c_str(), covered, penumbra, outside, worst);
  EXPECT_GT(penumbra, 200u) << label;
  EXPECT_LE(double(outside), 0.001 * double(covered)) << label;
}

TEST(ReferenceExact, AgreesWithMonteCarloOnTheSphereGrid) {
  expect_agreement(sb::test::scene_of_type("sphere_grid", {{"grid", 3}}), "sphere grid");
}

TEST(ReferenceExact, AgreesWithMonteCarloOnAJeep) {
  expect_agreement(sb::test::scene_of_type("jeep", {}), "jeep");
}

TEST(ReferenceExact, AgreesWithMonteCarloOnAGltfFile) {
  expect_agreement(sb::test::scene_of_type(
                       "gltf", {{"file", SHADOWBENCH_SOURCE_DIR "/configs/models/jeep.glb"}}),
                   "configs/models/jeep.glb");
}

}  // namespace
