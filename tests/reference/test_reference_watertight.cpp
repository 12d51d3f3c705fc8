// Shadow rays through edges that neighbouring caster triangles share must
// not slip between them (Embree's robust mode, embree_scene.h).
//
// The scene puts every ray on such an edge: a segment light along x at
// height 4, receiver points on the line under it (z = 0, y = 0) and a caster
// plate at height 2, tessellated into a grid whose row of edges at z = 0
// lies in the plane of the light and the points. Each ray crosses the plate
// on that edge; the whole setup is turned by an arbitrary rotation, so that
// after float rounding the rays pass within rounding of the edge, on either
// side. The plate covers all of them: V = 0 exactly, for every sample, at
// every point, under sse2, avx2 and the CPU's best ISA. Embree's default
// mode lets some of the same rays through (about 10-12 % of them on an
// AVX-512 machine).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "reference/embree_isa.h"
#include "reference/embree_scene.h"
#include "reference/pixel_rays.h"
#include "reference/reference.h"
#include "reference/stratify.h"

namespace {

namespace ref = sb::reference;
using sb::core::ImageF;

constexpr int kPoints = 64;
constexpr int kWatertightSpp = 256;
constexpr int kCells = 12;  // per side of the plate: edges at z = -3, -2.5, ..., 3

struct WatertightEdgeScene {
  sb::core::Scene scene;
  sb::core::ImageF positions{kPoints, 1, 4, 0.0f}, normals{kPoints, 1, 3, 0.0f};

  WatertightEdgeScene() {
    const glm::dmat4 turn =
        glm::rotate(glm::rotate(glm::rotate(glm::dmat4(1.0), 0.37, {1, 0, 0}), 1.1, {0, 1, 0}),
                    -0.59, {0, 0, 1});
    const auto at = [&](double x, double y, double z) {
      return glm::vec3(turn * glm::dvec4(x, y, z, 1.0));
    };
    const auto along = [&](double x, double y, double z) {
      return glm::vec3(turn * glm::dvec4(x, y, z, 0.0));
    };
    sb::core::Mesh plate;
    plate.name = "tessellated plate";
    plate.casts_shadow = true;
    for (int i = 0; i <= kCells; ++i)
      for (int j = 0; j <= kCells; ++j)
        plate.positions.push_back(at(-3.0 + 6.0 * i / kCells, 2.0, -3.0 + 6.0 * j / kCells));
    const auto v = [](int i, int j) { return uint32_t(i * (kCells + 1) + j); };
    for (int i = 0; i < kCells; ++i)
      for (int j = 0; j < kCells; ++j)
        plate.indices.insert(plate.indices.end(), {v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j),
                                                   v(i + 1, j + 1), v(i, j + 1)});
    scene.meshes.push_back(std::move(plate));
    scene.light.center = at(0, 4, 0);
    scene.light.half_u = along(1, 0, 0);
    scene.light.half_v = glm::vec3(0.0f);
    scene.light.target = at(0, 0, 0);
    // The receivers: z = 0 below the light's line. Their ray offset moves
    // the origin along the normal (y), which stays in the plane z = 0.
    const glm::vec3 up = along(0, 1, 0);
    for (int k = 0; k < kPoints; ++k) {
      const glm::vec3 p = at(-1.5 + 3.0 * k / (kPoints - 1), 0.0, 0.0);
      for (int c = 0; c < 3; ++c) {
        positions.at(k, 0, c) = p[c];
        normals.at(k, 0, c) = up[c];
      }
      positions.at(k, 0, 3) = 1.0f;
    }
  }
};

// The ISAs to test: sse2, avx2 and this CPU's best, each once.
std::vector<std::string> isas_to_test() {
  std::vector<std::string> isas;
  for (const std::string& isa : {std::string("sse2"), std::string("avx2"), ref::best_cpu_isa()})
    if (ref::cpu_supports_isa(isa) && std::find(isas.begin(), isas.end(), isa) == isas.end())
      isas.push_back(isa);
  return isas;
}

// Rays of the same samples that reach the light with Embree's default mode:
// what the reference saw before it was robust.
size_t leaks_without_robust_mode(const WatertightEdgeScene& e, const std::string& isa) {
  namespace d = ref::detail;
  d::Device device(isa);
  const d::FlatScene casters(
      device, e.scene, [](const sb::core::Mesh& m) { return m.casts_shadow; }, false,
      d::Traversal::Fast);
  const d::Layout layout = d::make_layout(kWatertightSpp, d::Strata::AlongS);
  const d::RaySetup setup(e.scene, casters, layout, e.positions, e.normals, 1);
  d::FtzDazScope ftz;
  d::PixelRays rays(setup);
  std::vector<uint32_t> all(kWatertightSpp);
  for (uint32_t i = 0; i < kWatertightSpp; ++i) all[i] = i;
  std::vector<uint8_t> reached(kWatertightSpp);
  size_t leaks = 0;
  for (size_t pix = 0; pix < size_t(kPoints); ++pix) {
    rays.start(pix);
    rays.trace(all.data(), kWatertightSpp, reached.data());
    for (const uint8_t r : reached) leaks += r;
  }
  return leaks;
}

TEST(referenceWatertight, RaysThroughSharedEdgesStayInTheUmbra) {
  const WatertightEdgeScene e;
  ASSERT_TRUE(e.scene.light.is_segment());
  for (const std::string& isa : isas_to_test()) {
    SCOPED_TRACE("isa " + isa);
    const ref::Result r =
        ref::compute(e.scene, e.positions, e.normals, {kWatertightSpp, 1, "isa=" + isa});
    ASSERT_EQ(r.isa, isa);
    size_t lit = 0;
    for (int k = 0; k < kPoints; ++k) {
      EXPECT_EQ(r.visibility.data[size_t(k)], 0.0f) << "point " << k;
      EXPECT_EQ(r.std_error.data[size_t(k)], 0.0f) << "point " << k;
      lit += size_t(std::lround(r.visibility.data[size_t(k)] * float(kWatertightSpp)));
    }
    // The scene does probe the edges: Embree's default mode lets rays through.
    const size_t leaks = leaks_without_robust_mode(e, isa);
    EXPECT_GT(leaks, 0u);
    std::printf("%s: %zu of %d rays reach the light (without robust mode: %zu)\n", isa.c_str(), lit,
                kPoints * kWatertightSpp, leaks);
  }
}

}  // namespace
