#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/error.h"
#include "reference/ray_offset.h"
#include "reference/reference.h"
#include "test_scenes.h"

namespace {

using sb::core::ImageF;
namespace ref = sb::reference;

// ---- an occluder edge over a plane, solved exactly ---------------------------

// Area of {(x,z) in [-1,1]^2 : a x + b z < k} (clip the square, shoelace).
double halfplane_area(double a, double b, double k) {
  const std::vector<std::pair<double, double>> sq = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  std::vector<std::pair<double, double>> poly;
  for (size_t i = 0; i < sq.size(); ++i) {
    const auto p = sq[i], q = sq[(i + 1) % sq.size()];
    const double fp = a * p.first + b * p.second - k, fq = a * q.first + b * q.second - k;
    if (fp < 0) poly.push_back(p);
    if ((fp < 0) != (fq < 0)) {
      const double t = fp / (fp - fq);
      poly.emplace_back(p.first + t * (q.first - p.first), p.second + t * (q.second - p.second));
    }
  }
  double area = 0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const auto p = poly[i], q = poly[(i + 1) % poly.size()];
    area += p.first * q.second - q.first * p.second;
  }
  return 0.5 * std::fabs(area);
}

// Ground (receiver) at y = 0, light 2×2 at y = 10, and at y = 5 an occluder
// covering the half-plane a x + b z < 0, so its edge crosses the penumbra diagonally.
struct EdgeScene {
  double a = std::cos(0.5), b = std::sin(0.5);
  sb::core::Scene scene;
  EdgeScene() {
    scene.light = sbtest::square_light();
    scene.meshes.push_back(
        sbtest::quad("ground", {-3, 0, -3}, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}, false));
    const glm::vec3 e(float(-b), 0, float(a)), n(float(a), 0, float(b)), h(0, 5, 0);
    scene.meshes.push_back(sbtest::quad("occluder", h + 8.0f * e, h - 8.0f * e,
                                        h - 8.0f * e - 8.0f * n, h + 8.0f * e - 8.0f * n, true));
  }
  // Exact V for a ground point, for the shadow-ray origin the reference uses
  // (the ground is no caster: the offset follows p alone).
  double visibility(double px, double pz) const {
    const double h0 = double(ref::detail::kOffsetRelative) * std::max(std::fabs(px), std::fabs(pz));
    const double f = (5.0 - h0) / (10.0 - h0);
    const double k = -(1.0 - f) * (a * px + b * pz) / f;
    return 1.0 - halfplane_area(a, b, k) / 4.0;
  }
};

// A hand-made G-buffer of ground points on [-1.5,1.5]^2, seen from above.
std::pair<sb::core::ImageF, sb::core::ImageF> ground_gbuffer(int w, int h) {
  sb::core::ImageF pos(w, h, 4), nrm(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      pos.at(x, y, 0) = -1.5f + 3.0f * (float(x) + 0.5f) / float(w);
      pos.at(x, y, 2) = -1.5f + 3.0f * (float(y) + 0.5f) / float(h);
      pos.at(x, y, 3) = 1.0f;
      nrm.at(x, y, 1) = 1.0f;
    }
  return {pos, nrm};
}

TEST(reference, HalfCoveredLightGivesOneHalf) {
  EdgeScene es;
  sb::core::ImageF pos(1, 1, 4), nrm(1, 1, 3);
  pos.data = {0, 0, 0, 1};
  nrm.data = {0, 1, 0};
  const ref::Result r = ref::compute(es.scene, pos, nrm, {256, 1});
  EXPECT_NEAR(es.visibility(0, 0), 0.5, 1e-12);
  EXPECT_GT(r.std_error.data[0], 0.0f);
  EXPECT_LT(r.std_error.data[0], 0.05f);
  EXPECT_LE(std::fabs(r.visibility.data[0] - 0.5), 4.0 * r.std_error.data[0]);
  EXPECT_EQ(r.method, "embree_stratified_packet16");
  EXPECT_EQ(r.spp, 256);
  EXPECT_FALSE(r.from_cache);
}

TEST(reference, MatchesTheExactAnswerWithinItsStdError) {
  EdgeScene es;
  const auto [pos, nrm] = ground_gbuffer(48, 36);
  const int spp = 256;
  const ref::Result r = ref::compute(es.scene, pos, nrm, {spp, 7});
  const double edge = std::fabs(es.a) + std::fabs(es.b);
  int lit = 0, blocked = 0, penumbra = 0, outliers = 0;
  double err2 = 0, se2 = 0;
  for (int y = 0; y < pos.height; ++y)
    for (int x = 0; x < pos.width; ++x) {
      const double px = pos.at(x, y, 0), pz = pos.at(x, y, 2);
      const double v = r.visibility.at(x, y), se = r.std_error.at(x, y);
      // Distance of the edge's projection from the light's centre, in light half-sizes.
      const double k = -(es.a * px + es.b * pz);
      if (k < -edge - 1e-3) {
        ++lit;
        EXPECT_EQ(v, 1.0) << x << "," << y;
        EXPECT_EQ(se, 0.0);
      } else if (k > edge + 1e-3) {
        ++blocked;
        EXPECT_EQ(v, 0.0) << x << "," << y;
        EXPECT_EQ(se, 0.0);
      } else if (std::fabs(k) < edge - 1e-3) {
        ++penumbra;
        const double e = v - es.visibility(px, pz);
        err2 += e * e;
        se2 += se * se;
        if (std::fabs(e) > 3.0 * se + 1.0 / spp) ++outliers;
      }
    }
  ASSERT_GT(lit, 50);
  ASSERT_GT(blocked, 50);
  ASSERT_GT(penumbra, 300);
  const double rmse = std::sqrt(err2 / penumbra), rms_se = std::sqrt(se2 / penumbra);
  // The stated error is the right size: not far below the true error, not far above.
  EXPECT_GT(rmse / rms_se, 0.45) << rmse << " " << rms_se;
  EXPECT_LT(rmse / rms_se, 1.2) << rmse << " " << rms_se;
  EXPECT_LT(outliers, penumbra / 50) << outliers << " of " << penumbra;
  RecordProperty("true_over_stated", std::to_string(rmse / rms_se));
  RecordProperty("outliers", std::to_string(outliers) + "/" + std::to_string(penumbra));
  // mean_std_error: σ over the soft estimates. The noise figure the RMSE
  // warning uses: sqrt(mean noise²) over the penumbra, each pixel's noise its
  // σ or, where its samples agreed, its stop bound; never below the mean
  // (Jensen).
  double sigma = 0, noise2 = 0;
  int soft = 0, in_penumbra = 0;
  for (size_t i = 0; i < r.visibility.data.size(); ++i) {
    if (r.visibility.data[i] > 0.0f && r.visibility.data[i] < 1.0f) {
      sigma += r.std_error.data[i];
      ++soft;
    }
    if (r.penumbra[i]) {
      const double noise = std::max(r.std_error.data[i], r.stop_bound.data[i]);
      noise2 += noise * noise;
      ++in_penumbra;
    }
  }
  ASSERT_GT(soft, 0);
  ASSERT_GE(in_penumbra, soft);
  EXPECT_NEAR(r.mean_std_error, sigma / soft, 1e-9);
  EXPECT_NEAR(r.penumbra_rms_std_error, std::sqrt(noise2 / in_penumbra), 1e-9);
  EXPECT_GE(r.penumbra_rms_std_error, r.penumbra_mean_std_error);
}

TEST(reference, BackgroundIsLitWithoutError) {
  EdgeScene es;
  auto [pos, nrm] = ground_gbuffer(16, 12);
  for (int y = 0; y < pos.height; ++y)
    for (int x = 0; x < pos.width; x += 2) {
      pos.at(x, y, 0) = std::numeric_limits<float>::quiet_NaN();  // never read
      pos.at(x, y, 3) = 0.0f;
    }
  const ref::Result r = ref::compute(es.scene, pos, nrm, {64, 1});
  int shadowed = 0;
  for (int y = 0; y < pos.height; ++y)
    for (int x = 0; x < pos.width; ++x) {
      if (x % 2 == 0) {
        EXPECT_EQ(r.visibility.at(x, y), 1.0f);
        EXPECT_EQ(r.std_error.at(x, y), 0.0f);
      } else {
        shadowed += r.visibility.at(x, y) < 1.0f;
      }
    }
  EXPECT_GT(shadowed, 0);
}

TEST(reference, NoCastersMeansFullyLit) {
  EdgeScene es;
  es.scene.meshes[1].casts_shadow = false;
  const auto [pos, nrm] = ground_gbuffer(8, 6);
  const ref::Result r = ref::compute(es.scene, pos, nrm, {16, 1});
  for (size_t i = 0; i < pos.pixel_count(); ++i) {
    EXPECT_EQ(r.visibility.data[i], 1.0f);
    EXPECT_EQ(r.std_error.data[i], 0.0f);
  }
  EXPECT_EQ(r.mean_std_error, 0.0);
}

TEST(reference, LightBelowTheTangentPlaneIsOccludedByTheSurface) {
  EdgeScene es;
  es.scene.meshes[1].casts_shadow = false;  // nothing but the horizon
  const float h = 0.5f * es.scene.light.center.y;
  sb::core::ImageF pos(3, 1, 4), nrm(3, 1, 3);
  // A wall point under the light's centre facing +x: half the light lies behind it.
  // A ground point seen from below (normal down): the light is entirely behind.
  // A ground point seen from above: fully lit.
  pos.data = {es.scene.light.center.x, h, es.scene.light.center.z, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  nrm.data = {1, 0, 0, 0, -1, 0, 0, 1, 0};
  const ref::Result r = ref::compute(es.scene, pos, nrm, {256, 1});
  EXPECT_NEAR(r.visibility.data[0], 0.5, 0.02);
  EXPECT_EQ(r.visibility.data[1], 0.0f);
  EXPECT_EQ(r.std_error.data[1], 0.0f);
  EXPECT_EQ(r.visibility.data[2], 1.0f);
}

TEST(reference, RejectsBadInput) {
  EdgeScene es;
  auto [pos, nrm] = ground_gbuffer(4, 3);
  EXPECT_THROW(ref::compute(es.scene, pos, nrm, {0, 1}), std::invalid_argument);
  EXPECT_THROW(ref::compute(es.scene, pos, nrm, {16, 1, "isa=avx9"}), std::invalid_argument);
  EXPECT_THROW(ref::compute(es.scene, sb::core::ImageF(4, 3, 3), nrm, {16, 1}),
               std::invalid_argument);
  EXPECT_THROW(ref::compute(es.scene, pos, sb::core::ImageF(5, 3, 3), {16, 1}),
               std::invalid_argument);
  sb::core::ImageF bad = pos;
  bad.at(1, 1, 1) = std::numeric_limits<float>::infinity();
  EXPECT_THROW(ref::compute(es.scene, bad, nrm, {16, 1}), std::invalid_argument);
  sb::core::Scene broken = es.scene;
  broken.meshes[1].indices[2] = 99;
  EXPECT_THROW(ref::compute(broken, pos, nrm, {16, 1}), sb::core::InputError);
}

// ---- a sphere over a plane, positions by primary rays -------------------------

TEST(reference, TraceGBufferSeesTheGround) {
  sb::core::Scene s;
  s.meshes.push_back(sbtest::quad("ground", {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, false));
  s.camera.eye = {0, 5, 5};
  s.camera.target = {0, 0, 0};
  const ref::GBuffer g = ref::trace_gbuffer(s, 33, 33);
  ASSERT_EQ(g.positions.channels, 4);
  ASSERT_EQ(g.normals.channels, 3);
  EXPECT_EQ(g.positions.at(16, 16, 3), 1.0f);
  EXPECT_NEAR(g.positions.at(16, 16, 0), 0.0f, 1e-4f);
  EXPECT_NEAR(g.positions.at(16, 16, 1), 0.0f, 1e-6f);
  EXPECT_NEAR(g.positions.at(16, 16, 2), 0.0f, 1e-4f);
  EXPECT_FLOAT_EQ(g.normals.at(16, 16, 1), 1.0f);
  EXPECT_EQ(g.positions.at(0, 0, 3), 0.0f);  // corners look past the small ground
  // Row 0 is on top: upper rows look further away (towards -z).
  int top = 0, bottom = 32;
  while (g.positions.at(16, top, 3) == 0.0f) ++top;
  while (g.positions.at(16, bottom, 3) == 0.0f) --bottom;
  EXPECT_LT(g.positions.at(16, top, 2), g.positions.at(16, bottom, 2));
}

TEST(reference, TraceGBufferNormalsFaceTheCameraOnBackFaces) {
  // The same ground wound clockwise from above: its cross product points
  // down, away from the camera; the G-buffer's normal must still face it.
  sb::core::Scene s;
  s.meshes.push_back(sbtest::quad("ground", {-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}, false));
  s.camera.eye = {0, 5, 5};
  s.camera.target = {0, 0, 0};
  const ref::GBuffer g = ref::trace_gbuffer(s, 33, 33);
  ASSERT_EQ(g.positions.at(16, 16, 3), 1.0f);
  EXPECT_FLOAT_EQ(g.normals.at(16, 16, 1), 1.0f);
}

// RMS of v - v_ref over the penumbra of `mask` (default: of v_ref).
double penumbra_rmse(const sb::core::ImageF& v, const sb::core::ImageF& v_ref, int* count = nullptr,
                     const sb::core::ImageF* mask = nullptr) {
  if (!mask) mask = &v_ref;
  double e2 = 0;
  int n = 0;
  for (size_t i = 0; i < v.data.size(); ++i)
    if (mask->data[i] > 0.0f && mask->data[i] < 1.0f) {
      const double e = double(v.data[i]) - v_ref.data[i];
      e2 += e * e;
      ++n;
    }
  if (count) *count = n;
  return n ? std::sqrt(e2 / n) : 0.0;
}

double penumbra_rms(const sb::core::ImageF& se, const sb::core::ImageF& v_ref) {
  return penumbra_rmse(se, sb::core::ImageF(se.width, se.height, 1, 0.0f), nullptr, &v_ref);
}

TEST(reference, StratifiedConvergence) {
  const sb::core::Scene s = sbtest::sphere_over_plane();
  const ref::GBuffer g = ref::trace_gbuffer(s, 96, 72);
  const ref::Result r16 = ref::compute(s, g.positions, g.normals, {16, 3});
  const ref::Result r64 = ref::compute(s, g.positions, g.normals, {64, 3});
  const ref::Result r256 = ref::compute(s, g.positions, g.normals, {256, 4});
  const ref::Result r4096 = ref::compute(s, g.positions, g.normals, {4096, 5});
  int n = 0;
  const double e16 = penumbra_rmse(r16.visibility, r4096.visibility, &n);
  const double e64 = penumbra_rmse(r64.visibility, r4096.visibility);
  const double e256 = penumbra_rmse(r256.visibility, r4096.visibility);
  ASSERT_GT(n, 500);
  EXPECT_GT(e16, e64);
  EXPECT_GT(e64, e256);
  // Stratified sampling converges as ~N^-0.75 in penumbrae: 16× the samples
  // should cut the error ~8×, clearly more than the 4× of random sampling.
  EXPECT_GT(e16 / e256, 5.0) << e16 << " " << e256;
  // The stated error is the right size at every count.
  for (const ref::Result* r : {&r16, &r64, &r256}) {
    const double rmse = penumbra_rmse(r->visibility, r4096.visibility);
    const double rms_se = penumbra_rms(r->std_error, r4096.visibility);
    EXPECT_GT(rmse / rms_se, 0.45) << r->spp << ": " << rmse << " " << rms_se;
    EXPECT_LT(rmse / rms_se, 1.2) << r->spp << ": " << rmse << " " << rms_se;
    RecordProperty("true_over_stated_" + std::to_string(r->spp), std::to_string(rmse / rms_se));
  }
  RecordProperty("rmse16", std::to_string(e16));
  RecordProperty("rmse64", std::to_string(e64));
  RecordProperty("rmse256", std::to_string(e256));
  RecordProperty("penumbra_pixels", n);
}

TEST(reference, BitIdenticalForAnyThreadCount) {
  const sb::core::Scene s = sbtest::sphere_over_plane();
  const ref::GBuffer g = ref::trace_gbuffer(s, 40, 30);
  const auto run = [&](size_t threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return ref::compute(s, g.positions, g.normals, {64, 11});
  };
  const ref::Result a = run(1), b = run(2), c = run(2);
  const size_t bytes = a.visibility.data.size() * sizeof(float);
  EXPECT_EQ(std::memcmp(a.visibility.data.data(), b.visibility.data.data(), bytes), 0);
  EXPECT_EQ(std::memcmp(a.std_error.data.data(), b.std_error.data.data(), bytes), 0);
  EXPECT_EQ(std::memcmp(b.visibility.data.data(), c.visibility.data.data(), bytes), 0);
  EXPECT_EQ(std::memcmp(b.std_error.data.data(), c.std_error.data.data(), bytes), 0);
  EXPECT_EQ(a.mean_std_error, b.mean_std_error);
  // A different seed gives a different (but equally valid) estimate.
  const ref::Result d = ref::compute(s, g.positions, g.normals, {64, 12});
  EXPECT_NE(std::memcmp(a.visibility.data.data(), d.visibility.data.data(), bytes), 0);
}

}  // namespace
