// The uniform reference's proven pixels (reference/uniform_trace.h): where
// the proofs hold, a pixel whose first packet agrees and is proven traces no
// more rays, and the images are bit for bit those of every sample traced
// (the same function without proofs); the penumbra is still the exact
// visibility's (ExactVisibility::partly_lit) wherever the samples agreed.
// Sphere grid and a jeep at 160×120, 64 spp.
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../common/scene_of_type.h"
#include "reference/embree_isa.h"
#include "reference/embree_scene.h"
#include "reference/exact_visibility.h"
#include "reference/pixel_rays.h"
#include "reference/reference.h"
#include "reference/stratify.h"
#include "reference/uniform_trace.h"
#include "scenes/topology.h"

// Named, not anonymous: the unity build shares one translation unit.
namespace uniform_trace_test {

namespace d = sb::reference::detail;
using sb::core::Mesh;
using sb::core::Scene;
using sb::reference::GBuffer;

constexpr int kWidth = 160, kHeight = 120;

std::vector<bool> closed_casters(const Scene& scene) {
  std::vector<bool> closed;
  for (const Mesh& m : scene.meshes)
    closed.push_back(m.casts_shadow && !m.double_sided && !m.alpha_tested() &&
                     sb::analyse_topology(m).closed());
  return closed;
}

size_t differing(const sb::core::ImageF& a, const sb::core::ImageF& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.data.size(); ++i) n += a.data[i] != b.data[i];
  return n;
}

void expect_same_images_with_fewer_rays(const Scene& scene) {
  const GBuffer g = sb::reference::trace_gbuffer(scene, kWidth, kHeight);
  d::Device device(sb::reference::resolve_isa(sb::reference::default_embree_config()));
  const d::FlatScene casters(
      device, scene, [](const Mesh& m) { return m.casts_shadow; }, true);
  const sb::reference::ExactVisibility exact(scene, closed_casters(scene));
  const d::Layout layout = d::make_layout(64);
  const d::RaySetup setup(scene, casters, layout, g.positions, g.normals, 7);
  const d::UniformImages every = d::trace_uniform(setup, nullptr);
  const d::UniformImages proven = d::trace_uniform(setup, &exact);
  EXPECT_EQ(differing(every.visibility, proven.visibility), 0u);
  EXPECT_EQ(differing(every.std_error, proven.std_error), 0u);
  EXPECT_EQ(differing(every.stop_bound, proven.stop_bound), 0u);
  size_t covered = 0, settled = 0;
  for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
    covered += d::covered(g.positions, i);
    settled += proven.settled[i] == d::Settled::Proven;
    EXPECT_EQ(every.settled[i], d::Settled::Unknown);
  }
  std::printf("%zu of %zu covered pixels proven (no rays past the first packet)\n", settled,
              covered);
  // Most of the image is lit ground or umbra: the proofs must cut rays there.
  EXPECT_GT(settled, covered / 2);
}

TEST(ReferenceUniformTrace, ProvenPixelsGetTheValuesEverySampleGives) {
  expect_same_images_with_fewer_rays(sb::test::scene_of_type("sphere_grid", {{"grid", 3}}));
  expect_same_images_with_fewer_rays(sb::test::scene_of_type("jeep"));
}

// The region is the exact visibility's wherever the samples agreed, however
// tracing settled them: every pixel against partly_lit itself.
TEST(ReferenceUniformTrace, ThePenumbraIsStillPartlyLitWhereTheSamplesAgree) {
  for (const std::string type : {"sphere_grid", "jeep"}) {
    const Scene scene = sb::test::scene_of_type(type, {});
    const GBuffer g = sb::reference::trace_gbuffer(scene, kWidth, kHeight);
    const sb::reference::Result r =
        sb::reference::compute(scene, g.positions, g.normals, sb::reference::Settings(64, 7));
    ASSERT_EQ(r.penumbra_source, sb::reference::kPenumbraExact);
    const sb::reference::ExactVisibility exact(scene, closed_casters(scene));
    size_t region = 0;
    for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
      if (!d::covered(g.positions, i)) continue;
      const float v = r.visibility.data[i];
      const float* p = &g.positions.data[i * 4];
      const float* n = &g.normals.data[i * size_t(g.normals.channels)];
      const bool soft = (v > 0.0f && v < 1.0f) || exact.partly_lit(glm::dvec3(p[0], p[1], p[2]),
                                                                   glm::dvec3(n[0], n[1], n[2]));
      EXPECT_EQ(r.penumbra[i] != 0, soft) << type << " pixel " << i;
      region += soft;
    }
    EXPECT_GT(region, 100u) << type;
  }
}

}  // namespace uniform_trace_test
