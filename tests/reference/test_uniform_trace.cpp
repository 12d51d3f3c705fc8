// The uniform reference's proven pixels (reference/uniform_trace.h): where
// the proofs hold, a pixel whose first packet agrees and is proven traces no
// more rays, and the images are bit for bit those of every sample traced
// (the same function without proofs); the penumbra is still the exact
// visibility's (ExactVisibility::partly_lit) wherever the samples agreed.
// Sphere grid and a jeep at 160×120, 64 spp.
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <random>
#include <span>
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

// A scene's G-buffer, its casters in Embree and its exact visibility.
struct Traced {
  explicit Traced(const Scene& scene)
      : g(sb::reference::trace_gbuffer(scene, kWidth, kHeight)),
        device(sb::reference::resolve_isa(sb::reference::default_embree_config())),
        casters(
            device, scene, [](const Mesh& m) { return m.casts_shadow; }, true),
        exact(scene, closed_casters(scene)) {}
  GBuffer g;
  d::Device device;
  d::FlatScene casters;
  sb::reference::ExactVisibility exact;
};

void expect_same_images_with_fewer_rays(const Scene& scene) {
  const Traced traced(scene);
  const GBuffer& g = traced.g;
  const sb::reference::ExactVisibility& exact = traced.exact;
  const d::Layout layout = d::make_layout(64);
  const d::RaySetup setup(scene, traced.casters, layout, g.positions, g.normals, 7);
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

// The tile proofs (ExactVisibility::sees_candidates, hides_candidates) on
// random tiles of random sphere grids (sizes, stacked layers, coarse and
// fine spheres, small and large lights) and a jeep, against tracing every
// sample of every pixel (64 spp): a tile proven whole has every sample of
// every pixel lit (or occluded); a point's proof with the tile's candidates
// gives the answer of its own walk, and holds only where its samples agree.
void expect_tile_proofs_sound(const Scene& scene, std::mt19937& rng, size_t& whole_lit,
                              size_t& whole_dark) {
  const Traced traced(scene);
  const GBuffer& g = traced.g;
  const sb::reference::ExactVisibility& exact = traced.exact;
  const d::Layout layout = d::make_layout(64);
  const d::RaySetup setup(scene, traced.casters, layout, g.positions, g.normals, 3);
  d::PixelRays rays(setup);
  std::vector<uint32_t> all(64);
  for (uint32_t i = 0; i < 64; ++i) all[i] = i;
  std::vector<uint8_t> reached(64);
  using Point = sb::reference::ExactVisibility::ProofPoint;
  std::uniform_int_distribution<int> side(1, 6), px(0, kWidth - 1), py(0, kHeight - 1);
  // Half the tiles start at a pixel its own walk proves dark (umbra is
  // rare at this size).
  std::vector<size_t> dark_pixels;
  for (size_t pix = 0; pix < g.positions.pixel_count(); ++pix) {
    if (!d::covered(g.positions, pix)) continue;
    rays.start(pix);
    const float* p = &g.positions.data[pix * 4];
    if (exact.hides_whole_light(glm::dvec3(p[0], p[1], p[2]), glm::dvec3(rays.origin()),
                                glm::dvec3(rays.normal())))
      dark_pixels.push_back(pix);
  }
  for (int trial = 0; trial < 150; ++trial) {
    int x0 = px(rng), y0 = py(rng);
    if (trial % 2 == 1 && !dark_pixels.empty()) {
      const size_t pix = dark_pixels[size_t(px(rng) * kHeight + py(rng)) % dark_pixels.size()];
      x0 = int(pix % size_t(kWidth));
      y0 = int(pix / size_t(kWidth));
    }
    const int x1 = std::min(kWidth, x0 + side(rng)), y1 = std::min(kHeight, y0 + side(rng));
    std::vector<Point> points;
    std::vector<size_t> lit_samples;  // per point: of 64
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const size_t pix = size_t(y) * size_t(kWidth) + size_t(x);
        if (!d::covered(g.positions, pix)) continue;
        rays.start(pix);
        const float* p = &g.positions.data[pix * 4];
        points.push_back(
            {glm::dvec3(p[0], p[1], p[2]), glm::dvec3(rays.origin()), glm::dvec3(rays.normal())});
        rays.trace(all.data(), 64, reached.data());
        size_t count = 0;
        for (uint8_t r : reached) count += r;
        lit_samples.push_back(count);
      }
    sb::reference::ExactVisibility::TileCandidates lit, dark;
    exact.sees_candidates(points, lit);
    exact.hides_candidates(points, dark);
    for (size_t k = 0; k < points.size(); ++k) {
      const Point& q = points[k];
      if (lit.whole) {
        EXPECT_EQ(lit_samples[k], 64u) << "tile " << x0 << "," << y0;
      }
      if (dark.whole) {
        EXPECT_EQ(lit_samples[k], 0u) << "tile " << x0 << "," << y0;
      }
      const bool sees = exact.sees_whole_light(q, lit), hides = exact.hides_whole_light(q, dark);
      EXPECT_EQ(sees, exact.sees_whole_light(q.surface, q.origin, q.n));
      EXPECT_EQ(hides, exact.hides_whole_light(q.surface, q.origin, q.n));
      if (sees) {
        EXPECT_EQ(lit_samples[k], 64u);
      }
      if (hides) {
        EXPECT_EQ(lit_samples[k], 0u);
      }
    }
    whole_lit += lit.whole && !points.empty();
    whole_dark += dark.whole && !points.empty();
  }
}

TEST(ReferenceUniformTrace, TileProofsNeverContradictASample) {
  std::mt19937 rng(65);
  size_t whole_lit = 0, whole_dark = 0;
  for (int i = 0; i < 6; ++i) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const nlohmann::json params{
        {"grid", 2 + int(4 * u(rng))},       {"layers", 1 + int(2 * u(rng))},
        {"slices", 6 + int(20 * u(rng))},    {"stacks", 4 + int(16 * u(rng))},
        {"radius", 0.3 + 0.4 * u(rng)},      {"spacing", 1.2 + 1.0 * u(rng)},
        {"height", 0.5 + 1.0 * u(rng)},      {"light_size", 0.5 + 3.0 * u(rng)},
        {"light_height", 4.0 + 8.0 * u(rng)}};
    SCOPED_TRACE(params.dump());
    expect_tile_proofs_sound(sb::test::scene_of_type("sphere_grid", params), rng, whole_lit,
                             whole_dark);
  }
  expect_tile_proofs_sound(sb::test::scene_of_type("jeep"), rng, whole_lit, whole_dark);
  std::printf("%zu tiles proven lit, %zu dark, of %d\n", whole_lit, whole_dark, 7 * 150);
  // The proofs must hold somewhere for the test to test them.
  EXPECT_GT(whole_lit, 20u);
  EXPECT_GT(whole_dark, 5u);
}

}  // namespace uniform_trace_test
