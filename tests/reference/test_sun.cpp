// The sun's references against closed forms. A plate's straight edge at
// height h over the ground hides, from a ground point, the directions on one
// side of a line through the sun's disk (as projected onto the plane at unit
// distance along its axis, core::AreaLight's definition of the sun's V): V
// is one minus a circular segment's share of the disk. With the sun tilted
// by θ about the edge's direction, the line lies at c·t from the disk's
// centre, t = tan(diameter / 2) and c = tan(atan(−x/h) − θ) / t, x the
// point's distance past the edge's foot; the unit disk's share below c is
// F(c) = (c·√(1−c²) + asin c + π/2) / π. The horizon cuts the disk alike
// when the sun is low: the directions below it are a segment too. Both
// references see from the point raised by their ray offset ε
// (ray_offset.h), so the closed form puts the point at height ε: under a
// tilted sun that moves the penumbra by ε·tan θ, about 1e-4 of V here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "../common/scene_of_type.h"
#include "core/scene_types.h"
#include "reference/exact_visibility.h"
#include "reference/pixel_rays.h"
#include "reference/ray_offset.h"
#include "reference/reference.h"
#include "scenes/sphere_grid.h"

namespace {

using sb::core::ImageF;
using sb::core::Scene;
namespace ref = sb::reference;

// The unit disk's share below the line x = c.
double share_below(double c) {
  c = std::clamp(c, -1.0, 1.0);
  return (c * std::sqrt(1.0 - c * c) + std::asin(c) + std::numbers::pi / 2) / std::numbers::pi;
}

// V of a ground point x past the edge of a plate at height h covering
// x < 0, under a sun of diameter `diameter` tilted by θ towards +x, seen
// from the point raised by the references' ray offset.
double edge_visibility(double x, double h, double diameter, double theta) {
  const double t = std::tan(0.5 * diameter);
  const double eps = ref::detail::offset_from({x, 0.0, 0.0}, 0.0);
  return 1.0 - share_below(std::tan(std::atan(-x / (h - eps)) - theta) / t);
}

// A square plate (open, both sides cast) of half size 50 with its edge on
// x = 0 at height h, over a ground that casts nothing; the sun tilted by θ
// from overhead towards +x.
Scene plate_under_sun(double h, double diameter, double theta) {
  Scene s;
  sb::core::Mesh plate;
  plate.name = "plate";
  const float y = float(h);
  plate.positions = {{-100, y, -50}, {0, y, -50}, {0, y, 50}, {-100, y, 50}};
  plate.normals.assign(4, {0, 1, 0});
  plate.indices = {0, 2, 1, 0, 3, 2};
  plate.double_sided = true;
  s.meshes.push_back(plate);
  s.meshes.push_back(sb::make_ground_plane("ground", glm::vec3(0), 200.0f));
  s.meshes.back().casts_shadow = false;
  s.light = sb::core::make_sun_light({std::sin(theta), std::cos(theta), 0.0}, {0, 0, 0},
                                     float(diameter), 500.0f);
  return s;
}

// Ground points across the edge's penumbra (and a little beyond), at z = 0.
std::vector<double> across_penumbra(double h, double diameter, double theta, int count) {
  const double t = std::tan(0.5 * diameter);
  // Where c = ±1: x = −h·tan(θ ± atan t).
  const double lo = -h * std::tan(theta + std::atan(t)), hi = -h * std::tan(theta - std::atan(t));
  std::vector<double> xs;
  for (int i = 0; i < count; ++i) {
    const double f = -0.1 + 1.2 * (i + 0.5) / count;
    xs.push_back(lo + f * (hi - lo));
  }
  return xs;
}

struct Points {
  ImageF positions, normals;
  Points(const std::vector<double>& xs, glm::vec3 normal = {0, 1, 0})
      : positions(int(xs.size()), 1, 4), normals(int(xs.size()), 1, 3) {
    for (size_t i = 0; i < xs.size(); ++i) {
      positions.at(int(i), 0, 0) = float(xs[i]);
      positions.at(int(i), 0, 3) = 1.0f;
      for (int c = 0; c < 3; ++c) normals.at(int(i), 0, c) = normal[c];
    }
  }
};

void expect_exact_edge(double h, double diameter, double theta) {
  const Scene s = plate_under_sun(h, diameter, theta);
  const ref::ExactVisibility exact(s);
  ASSERT_EQ(exact.unsupported(), "");
  double worst = 0.0;
  int soft = 0;
  for (const double x : across_penumbra(h, diameter, theta, 41)) {
    // The point as float, as a G-buffer holds it.
    const double xf = double(float(x));
    const double want = edge_visibility(xf, h, diameter, theta);
    const double got = exact.visibility({xf, 0.0, 0.0}, {0.0, 1.0, 0.0});
    worst = std::max(worst, std::fabs(got - want));
    soft += want > 0.01 && want < 0.99;
    EXPECT_NEAR(got, want, 1e-4) << "h " << h << ", x " << xf;
  }
  EXPECT_GE(soft, 25);  // the points do span the penumbra
  std::printf("h %.1f, diameter %.2f°, tilt %.0f°: worst |exact - closed form| %.2e\n", h,
              diameter * 180 / std::numbers::pi, theta * 180 / std::numbers::pi, worst);
}

TEST(ReferenceSun, ExactPlateEdgeMatchesTheCircularSegmentAtTwoHeights) {
  const double real_sun = 0.53 * std::numbers::pi / 180;
  expect_exact_edge(1.0, real_sun, 0.0);
  expect_exact_edge(4.0, real_sun, 0.0);
  expect_exact_edge(1.0, 5.0 * std::numbers::pi / 180, 0.0);
}

TEST(ReferenceSun, ExactPlateEdgeMatchesUnderATiltedSun) {
  expect_exact_edge(2.0, 3.0 * std::numbers::pi / 180, 35.0 * std::numbers::pi / 180);
  expect_exact_edge(0.5, 0.53 * std::numbers::pi / 180, -60.0 * std::numbers::pi / 180);
}

// Monte Carlo: each point within 4σ (σ its own standard error, or one
// sample's weight where all agreed), and the mean error over the points
// within 4 standard errors of the mean.
void expect_sampled_edge(double h, double diameter, double theta, bool adaptive) {
  const Scene s = plate_under_sun(h, diameter, theta);
  const std::vector<double> xs = across_penumbra(h, diameter, theta, 64);
  const Points pts(xs);
  ref::Settings settings(256, 7);
  if (adaptive) {
    settings.adaptive = true;
    settings.pilot_spp = 4;
    settings.target_std_error = 0.01;
  }
  const ref::Result r = ref::compute(s, pts.positions, pts.normals, settings);
  double sum = 0.0, variance = 0.0;
  for (size_t i = 0; i < xs.size(); ++i) {
    const double want = edge_visibility(double(float(xs[i])), h, diameter, theta);
    const double got = r.visibility.data[i];
    const double sigma = std::max(double(r.std_error.data[i]), 1.0 / 256.0);
    EXPECT_LE(std::fabs(got - want), 4.0 * sigma) << "h " << h << ", x " << xs[i];
    sum += got - want;
    variance += double(r.std_error.data[i]) * r.std_error.data[i];
  }
  const double n = double(xs.size());
  EXPECT_LE(std::fabs(sum / n), 4.0 * std::sqrt(variance) / n + 1e-3);
}

TEST(ReferenceSun, MonteCarloPlateEdgeIsWithinItsSigmaAtTwoHeights) {
  expect_sampled_edge(1.0, 2.0 * std::numbers::pi / 180, 0.0, false);
  expect_sampled_edge(4.0, 2.0 * std::numbers::pi / 180, 0.0, false);
  expect_sampled_edge(2.0, 3.0 * std::numbers::pi / 180, 35.0 * std::numbers::pi / 180, false);
}

TEST(ReferenceSun, AdaptiveMonteCarloPlateEdgeIsWithinItsSigma) {
  expect_sampled_edge(2.0, 2.0 * std::numbers::pi / 180, 0.0, true);
}

// A sun low enough for the horizon to cut its disk: the directions below
// it are hidden by the surface itself, in both references alike.
TEST(ReferenceSun, TheHorizonHidesTheDisksLowerPart) {
  const double diameter = 4.0 * std::numbers::pi / 180;
  const double t = std::tan(0.5 * diameter);
  for (const double elevation_deg : {0.0, 1.0, -1.5}) {
    const double theta = std::numbers::pi / 2 - elevation_deg * std::numbers::pi / 180;
    Scene s = plate_under_sun(1.0, diameter, theta);
    s.meshes.erase(s.meshes.begin());  // no plate: only the horizon
    // Directions d = a + t·q1·e1 + …, e1 = (cos θ, −sin θ, 0): below the
    // horizon where q1 > cot θ / t.
    const double want = share_below(1.0 / std::tan(theta) / t);
    const ref::ExactVisibility exact(s);
    EXPECT_NEAR(exact.visibility({0, 0, 0}, {0, 1, 0}), want, 1e-4) << elevation_deg;
    const Points pts({0.0, 3.0, -7.0});
    const ref::Result r = ref::compute(s, pts.positions, pts.normals, {1024, 3});
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(r.visibility.data[size_t(i)], want,
                  4.0 * std::max(double(r.std_error.data[size_t(i)]), 1.0 / 1024))
          << elevation_deg;
  }
}

TEST(ReferenceSun, UnionInsideTheDiskInClosedForm) {
  const double r = 0.3;
  const double disk = std::numbers::pi * r * r;
  // Half the square: half the disk.
  EXPECT_NEAR(ref::ExactVisibility::union_disk_area({{{-r, -r}, {0, -r}, {0, r}, {-r, r}}}, r),
              disk / 2, 1e-9 * disk);
  // The inscribed square: 2r², whatever the circle does outside it.
  const double s = r / std::sqrt(2.0);
  EXPECT_NEAR(ref::ExactVisibility::union_disk_area({{{-s, -s}, {s, -s}, {s, s}, {-s, s}}}, r),
              2 * r * r, 1e-9 * disk);
  // Two overlapping halves are the whole disk, counted once.
  EXPECT_NEAR(
      ref::ExactVisibility::union_disk_area(
          {{{-r, -r}, {0.1, -r}, {0.1, r}, {-r, r}}, {{-0.1, -r}, {r, -r}, {r, r}, {-0.1, r}}}, r),
      disk, 1e-9 * disk);
  // A frame around a hole of half size h: the disk but the hole.
  const double h = 0.05;
  const std::vector<std::vector<glm::dvec2>> frame = {{{-r, -r}, {r, -r}, {r, -h}, {-r, -h}},
                                                      {{-r, h}, {r, h}, {r, r}, {-r, r}},
                                                      {{-r, -h}, {-h, -h}, {-h, h}, {-r, h}},
                                                      {{h, -h}, {r, -h}, {r, h}, {h, h}}};
  EXPECT_NEAR(ref::ExactVisibility::union_disk_area(frame, r), disk - 4 * h * h, 1e-9 * disk);
}

// The concentric map keeps areas: equal strata of the square land on equal
// areas of the disk, so a stratified mean over a region is unbiased.
TEST(ReferenceSun, ConcentricMapKeepsAreas) {
  // The share of a fine grid's points that land within radius 0.5 is the
  // area ratio 1/4, and in the right half 1/2.
  int inside = 0, right = 0;
  const int n = 400;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const glm::vec2 q = ref::detail::concentric_disk(float(i + 0.5) / n, float(j + 0.5) / n);
      EXPECT_LE(glm::length(q), 1.0f + 1e-6f);
      inside += glm::length(q) < 0.5f;
      right += q.x > 0.0f;
    }
  EXPECT_NEAR(double(inside) / (n * n), 0.25, 0.005);
  EXPECT_NEAR(double(right) / (n * n), 0.5, 0.005);
}

}  // namespace

namespace {

// The two references on the outdoor street without its leaves (alpha masks
// have no exact form), at a G-buffer made by primary rays: on at least
// 99.9 % of the covered pixels they differ by at most four of the Monte
// Carlo reference's standard errors (or one sample's weight where its
// samples all agreed), as on the local-light scenes (test_exact_agreement).
TEST(ReferenceSun, ExactAndMonteCarloAgreeOnTheOutdoorStreet) {
  const Scene scene = sb::test::scene_of_type("outdoor", {{"leaves", 0}});
  ASSERT_TRUE(scene.light.is_sun());
  const ref::GBuffer g = ref::trace_gbuffer(scene, 160, 120);
  ref::Settings exact_settings;
  exact_settings.exact = true;
  const ref::Result exact = ref::compute(scene, g.positions, g.normals, exact_settings);
  ASSERT_EQ(exact.method, "exact_clipper") << exact.exact_fallback;
  const ref::Result mc = ref::compute(scene, g.positions, g.normals, {256, 1});
  size_t covered = 0, outside = 0, soft = 0, shadowed = 0;
  double worst = 0.0;
  for (size_t i = 0; i < g.positions.pixel_count(); ++i) {
    if (!(g.positions.data[i * 4 + 3] > 0.5f)) continue;
    ++covered;
    const double e = exact.visibility.data[i];
    const double d = std::fabs(e - double(mc.visibility.data[i]));
    soft += e > 0.0 && e < 1.0;
    shadowed += e < 0.5;
    worst = std::max(worst, d);
    outside += d > 4.0 * std::max(double(mc.std_error.data[i]), 1.0 / 256.0);
  }
  std::printf("outdoor: %zu covered px (%zu shadowed, %zu soft), %zu beyond 4 sigma, max %.4f\n",
              covered, shadowed, soft, outside, worst);
  EXPECT_GT(shadowed, 1000u);  // the street does have shadows to agree on
  EXPECT_GT(soft, 20u);
  EXPECT_LE(double(outside), 0.001 * double(covered));
}

}  // namespace
