// occlusion_texture's slicing (techniques/occlusion_texture/slicing.h), no
// GL: the central projection's frustum passes through the light's rectangle
// and holds every caster; each slab's kernel is the light seen from the
// point through the slab's plane, checked against rays traced to the
// light's corners; the slab shares skip a caster's own slab and fade the
// one in front of it in continuously, or fade a receiver's own slab in; and a light of no area or a
// caster on the light's plane neither divides by zero nor passes silently.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "core/error.h"
#include "occlusion_texture/slicing.h"

namespace sb::techniques::occlusion_texture {

using core::AreaLight;
using core::JobError;
using core::Mesh;
using core::Scene;

namespace {

// A square light of side `size` at y = 10 facing down (-y).
AreaLight square_light(float size) {
  AreaLight l;
  l.center = {0.0f, 10.0f, 0.0f};
  l.half_u = {0.5f * size, 0.0f, 0.0f};
  l.half_v = {0.0f, 0.0f, 0.5f * size};
  l.target = {0.0f, 0.0f, 0.0f};
  return l;
}

// Casters scattered over x, z in [-spread, spread] at heights 2..7, and a
// ground under them that casts nothing.
Scene scattered_casters(float light_size, float spread) {
  Scene s;
  s.light = square_light(light_size);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> xz(-spread, spread), y(2.0f, 7.0f);
  Mesh casters;
  casters.name = "casters";
  for (int i = 0; i < 60; ++i) {
    const glm::vec3 c(xz(rng), y(rng), xz(rng));
    for (const glm::vec3 d :
         {glm::vec3(0.1f, 0, 0), glm::vec3(0, 0.1f, 0), glm::vec3(0, 0, 0.1f)}) {
      casters.indices.push_back(uint32_t(casters.positions.size()));
      casters.positions.push_back(c + d);
    }
  }
  s.meshes.push_back(casters);
  Mesh ground;
  ground.name = "ground";
  ground.casts_shadow = false;
  ground.positions = {{-50, 0, -50}, {50, 0, -50}, {50, 0, 50}};
  ground.indices = {0, 1, 2};
  s.meshes.push_back(ground);
  return s;
}

TEST(OcclusionSlicing, TheCentralFrustumPassesThroughTheLightAndHoldsEveryCaster) {
  const Scene scene = scattered_casters(1.0f, 4.0f);
  const Slicing s = fit_slicing(scene, 16, Projection::Central);
  ASSERT_FALSE(s.no_casters);
  EXPECT_EQ(s.a, 1.0f);  // a centre at a finite distance behind the light
  float widest = 0.0f, z_lo = 1e30f, z_hi = -1e30f;
  for (const glm::vec3& p : scene.meshes[0].positions) {
    z_lo = std::min(z_lo, 10.0f - p.y);
    z_hi = std::max(z_hi, 10.0f - p.y);
    const glm::vec2 q = s.texture_coords(s.light.to_light(p));
    EXPECT_GE(q.x, 0.0f);
    EXPECT_LE(q.x, 1.0f);
    EXPECT_GE(q.y, 0.0f);
    EXPECT_LE(q.y, 1.0f);
    widest = std::max(widest, std::max(std::fabs(q.x - 0.5f), std::fabs(q.y - 0.5f)));
  }
  EXPECT_GT(widest, 0.49f) << "the frustum is wider than the casters need";
  // The light's corners lie on the frustum's sides (within the 1% margin).
  for (const float su : {-1.0f, 1.0f})
    for (const float sv : {-1.0f, 1.0f}) {
      const glm::vec3 corner =
          scene.light.center + su * scene.light.half_u + sv * scene.light.half_v;
      const glm::vec2 q = s.texture_coords(s.light.to_light(corner));
      EXPECT_NEAR(std::fabs(q.x - 0.5f), 0.5f / 1.01f, 1e-4f);
      EXPECT_NEAR(std::fabs(q.y - 0.5f), 0.5f / 1.01f, 1e-4f);
    }
  // Slabs cover the casters' depths, and nothing else.
  EXPECT_LT(s.z0, z_lo);
  EXPECT_NEAR(s.z0, z_lo, 0.01f);
  EXPECT_GT(s.z0 + 16.0f * s.thickness, z_hi);
  EXPECT_NEAR(s.z0 + 16.0f * s.thickness, z_hi, 0.01f);
}

TEST(OcclusionSlicing, CastersInsideTheLightsFootprintGetTheParallelProjectionOverIt) {
  const Scene scene = scattered_casters(10.0f, 4.0f);
  const Slicing s = fit_slicing(scene, 8, Projection::Central);
  EXPECT_EQ(s.a, 0.0f);
  EXPECT_NEAR(s.scale.x, 1.0f / (10.0f * 1.01f), 1e-6f);
}

// Each kernel corner is where the ray from p to a light corner crosses the
// slab's mid-plane, taken to texture coordinates.
TEST(OcclusionSlicing, EachSlabsKernelIsTheLightSeenFromThePointThroughTheSlabsPlane) {
  for (const Projection projection : {Projection::Central, Projection::Orthographic}) {
    const Scene scene = scattered_casters(1.5f, 3.0f);
    const Slicing s = fit_slicing(scene, 16, projection);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> xz(-6.0f, 6.0f), y(0.0f, 2.0f);
    for (int trial = 0; trial < 200; ++trial) {
      const glm::vec3 p(xz(rng), y(rng), xz(rng));
      const glm::vec3 pl = s.light.to_light(p);
      for (int k = 0; k < 16; ++k) {
        const float plane = s.mid_plane(k);
        glm::vec2 lo(1e30f), hi(-1e30f);
        for (const float su : {-1.0f, 1.0f})
          for (const float sv : {-1.0f, 1.0f}) {
            const glm::vec3 corner =
                scene.light.center + su * scene.light.half_u + sv * scene.light.half_v;
            const glm::vec3 cl = s.light.to_light(corner);
            const float t = (plane - pl.z) / (cl.z - pl.z);
            const glm::vec3 hit = pl + t * (cl - pl);
            const glm::vec2 q = s.texture_coords(hit);
            lo = glm::min(lo, q);
            hi = glm::max(hi, q);
          }
        const TextureBox box = s.kernel(pl, plane);
        EXPECT_NEAR(box.lo.x, lo.x, 1e-5f);
        EXPECT_NEAR(box.lo.y, lo.y, 1e-5f);
        EXPECT_NEAR(box.hi.x, hi.x, 1e-5f);
        EXPECT_NEAR(box.hi.y, hi.y, 1e-5f);
      }
    }
  }
}

TEST(OcclusionSlicing, WithOffsetOneASlabCountsOnceThePointIsPastItAndFadesInAcrossTheNext) {
  const Scene scene = scattered_casters(1.0f, 4.0f);
  const Slicing s = fit_slicing(scene, 8, Projection::Central);
  const float t = s.thickness;
  for (int k = 0; k < 8; ++k) {
    const float near_side = s.z0 + float(k) * t, far_side = near_side + t;
    EXPECT_EQ(s.share(near_side + 0.5f * t, k, 1.0f, LookupPlane::Mid).weight, 0.0f)
        << "its own slab";
    EXPECT_NEAR(s.share(far_side, k, 1.0f, LookupPlane::Mid).weight, 0.0f, 1e-5f);
    const SlabShare fading = s.share(far_side + 0.25f * t, k, 1.0f, LookupPlane::Mid);
    EXPECT_NEAR(fading.weight, 0.25f, 1e-4f);
    EXPECT_NEAR(fading.plane, near_side + 0.125f * t, 1e-4f)
        << "the middle of the part that counts";
    const SlabShare whole = s.share(far_side + 2.0f * t, k, 1.0f, LookupPlane::Mid);
    EXPECT_NEAR(whole.weight, 1.0f, 1e-5f);
    EXPECT_NEAR(whole.plane, s.mid_plane(k), 1e-5f);
  }
}

TEST(OcclusionSlicing, WithOffsetZeroAReceiversOwnSlabFadesInUpToItsDepth) {
  const Scene scene = scattered_casters(1.0f, 4.0f);
  const Slicing s = fit_slicing(scene, 8, Projection::Central);
  const float t = s.thickness;
  const float near_side = s.z0 + 3.0f * t;
  const SlabShare own = s.share(near_side + 0.6f * t, 3, 0.0f, LookupPlane::Mid);
  EXPECT_NEAR(own.weight, 0.6f, 1e-4f);
  EXPECT_NEAR(own.plane, near_side + 0.3f * t, 1e-4f);
  EXPECT_LT(own.plane, near_side + 0.6f * t) << "the plane lies in front of the point";
}

// The paper's lookup (§3): a slab that counts in full is read through the
// slice's far plane, and a slab fading in through the far side of the part
// that counts, which always lies in front of the point.
TEST(OcclusionSlicing, TheFarPlaneLookupReadsTheFarSideOfThePartThatCounts) {
  const Scene scene = scattered_casters(1.0f, 4.0f);
  const Slicing s = fit_slicing(scene, 8, Projection::Central);
  const float t = s.thickness;
  for (int k = 0; k < 8; ++k) {
    const float near_side = s.z0 + float(k) * t;
    const SlabShare whole = s.share(near_side + 3.0f * t, k, 1.0f, LookupPlane::Far);
    EXPECT_NEAR(whole.weight, 1.0f, 1e-5f);
    EXPECT_NEAR(whole.plane, s.far_plane(k), 1e-5f);
    const SlabShare fading = s.share(near_side + 1.4f * t, k, 1.0f, LookupPlane::Far);
    EXPECT_NEAR(fading.weight, 0.4f, 1e-4f);
    EXPECT_NEAR(fading.plane, near_side + 0.4f * t, 1e-4f);
  }
}

// The paper drops the slice that contains the point for every point: it
// has no caster/receiver split. The receiver-aware rule lets a point that
// casts nothing read its own slab.
TEST(OcclusionSlicing, TheSkipRuleGivesReceiversTheCastersOffsetAndReceiverAwareNone) {
  EXPECT_EQ(point_offset(SelfSlab::Skip, /*casts_shadow=*/false, 1.0f), 1.0f);
  EXPECT_EQ(point_offset(SelfSlab::Skip, /*casts_shadow=*/true, 1.0f), 1.0f);
  EXPECT_EQ(point_offset(SelfSlab::ReceiverAware, /*casts_shadow=*/false, 1.0f), 0.0f);
  EXPECT_EQ(point_offset(SelfSlab::ReceiverAware, /*casts_shadow=*/true, 1.0f), 1.0f);
}

// Sweeping p through three slabs moves every slab's weight and plane
// continuously (steps of 1/100 of a slab change them by about as much).
TEST(OcclusionSlicing, SharesChangeContinuouslyWithDepth) {
  const Scene scene = scattered_casters(1.0f, 4.0f);
  const Slicing s = fit_slicing(scene, 8, Projection::Central);
  const float t = s.thickness;
  for (const LookupPlane plane : {LookupPlane::Far, LookupPlane::Mid})
    for (const float offset : {0.0f, 0.5f, 1.0f}) {
      for (int k = 0; k < 8; ++k) {
        const float near_side = s.z0 + float(k) * t;
        SlabShare last = s.share(near_side, k, offset, plane);
        for (int i = 1; i <= 300; ++i) {
          const SlabShare now = s.share(near_side + 3.0f * t * float(i) / 300.0f, k, offset, plane);
          EXPECT_GE(now.weight, last.weight);
          EXPECT_LE(now.weight - last.weight, 1.0f / 100.0f + 1e-4f) << "a jump";
          if (last.weight > 0.0f) {
            EXPECT_LE(std::fabs(now.plane - last.plane), t / 100.0f + 1e-4f);
          }
          last = now;
        }
      }
    }
}

TEST(OcclusionSlicing, ALightOfNoAreaProjectsFromItsCentreWithFiniteCoordinatesAndPointKernels) {
  const Scene scene = scattered_casters(0.0f, 4.0f);
  const Slicing s = fit_slicing(scene, 4, Projection::Central);
  for (const glm::vec3& p : scene.meshes[0].positions) {
    const glm::vec2 q = s.texture_coords(s.light.to_light(p));
    ASSERT_TRUE(std::isfinite(q.x) && std::isfinite(q.y));
    EXPECT_GE(std::min(q.x, q.y), 0.0f);
    EXPECT_LE(std::max(q.x, q.y), 1.0f);
  }
  const TextureBox box = s.kernel(s.light.to_light({1.0f, 0.0f, 2.0f}), s.mid_plane(2));
  EXPECT_EQ(box.lo, box.hi);
  EXPECT_TRUE(std::isfinite(box.lo.x) && std::isfinite(box.lo.y));
}

TEST(OcclusionSlicing, ACasterOnTheLightsPlaneIsAJobErrorNamingTheMesh) {
  Scene scene = scattered_casters(1.0f, 4.0f);
  scene.meshes[0].positions[0].y = 10.0f;
  try {
    fit_slicing(scene, 4, Projection::Central);
    FAIL() << "no error";
  } catch (const JobError& e) {
    EXPECT_NE(std::string(e.what()).find("'casters'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sb::techniques::occlusion_texture
