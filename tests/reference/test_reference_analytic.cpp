// The reference on analytic shapes (Mesh::analytic): spheres occlude as
// exact spheres while the points stay on the triangles. Checked against
// exact answers: the shadow boundary of a sphere under a near-point light,
// the soft shadow of a sphere seen from below its centre, a mesh's own
// points (not occluded by its own sphere), a neighbour's sphere (occludes
// exactly), and the cache key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include "core/error.h"
#include "core/scene_types.h"
#include "reference/reference.h"
#include "scenes/sphere_grid.h"

namespace {

using sb::core::ImageF;
namespace ref = sb::reference;

// A G-buffer of one row: the given points and normals, all covered.
struct Points {
  std::vector<glm::vec3> p, n;
  void add(glm::vec3 point, glm::vec3 normal) {
    p.push_back(point);
    n.push_back(normal);
  }
  sb::core::ImageF positions() const {
    sb::core::ImageF img(int(p.size()), 1, 4);
    for (size_t i = 0; i < p.size(); ++i) {
      img.at(int(i), 0, 0) = p[i].x;
      img.at(int(i), 0, 1) = p[i].y;
      img.at(int(i), 0, 2) = p[i].z;
      img.at(int(i), 0, 3) = 1.0f;
    }
    return img;
  }
  sb::core::ImageF normals() const {
    sb::core::ImageF img(int(n.size()), 1, 3);
    for (size_t i = 0; i < n.size(); ++i)
      for (int c = 0; c < 3; ++c) img.at(int(i), 0, c) = n[i][c];
    return img;
  }
};

ref::Result trace(const sb::core::Scene& s, const Points& pts, int spp) {
  return ref::compute(s, pts.positions(), pts.normals(), {spp, 3});
}

// A UV sphere of the sphere grid's tessellation, with or without its shape.
sb::core::Mesh sphere(glm::vec3 c, float r, int slices, int stacks, bool analytic) {
  sb::core::Mesh m = sb::make_uv_sphere("sphere", c, r, slices, stacks);
  if (analytic) m.analytic = sb::core::AnalyticShape::sphere(c, r);
  return m;
}

// A near-point light: a square of side 2e-4 at l.
sb::core::AreaLight point_light(glm::vec3 l) {
  sb::core::AreaLight light;
  light.center = l;
  light.half_u = {1e-4f, 0, 0};
  light.half_v = {0, 0, 1e-4f};
  return light;
}

// Distance from c to the segment [a, b], in double.
double segment_distance(glm::dvec3 c, glm::dvec3 a, glm::dvec3 b) {
  const glm::dvec3 ab = b - a;
  const double t = std::clamp(glm::dot(c - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
  return glm::length(a + t * ab - c);
}

// ---- hard shadow of one sphere on the ground --------------------------------

// Sphere of radius 1 at height 2 under a near-point light off its axis: its
// shadow on the ground is an ellipse. Ground points 1% of the boundary's
// distance inside it must be occluded, 1% outside lit. The boundary is found
// by bisection on the exact test (segment to the light meets the ball), along
// 64 directions from the shadow of the centre (the ellipse is convex and
// holds it). The coarse tessellation (8 slices, 6 stacks) casts a smaller
// polygon and gets many of the inside points wrong.
TEST(referenceAnalytic, HardShadowOfASphereIsTheExactEllipse) {
  const glm::dvec3 c(0, 2, 0), l(2.5, 10, 1.5);
  const double r = 1.0;
  const auto shadowed = [&](glm::dvec3 q) { return segment_distance(c, q, l) < r; };
  const glm::dvec3 q0 = l + (c - l) * (l.y / (l.y - c.y));  // on the ground

  Points pts;
  std::vector<float> expected;
  constexpr int kDirections = 64;
  constexpr double kMargin = 0.01;
  for (int k = 0; k < kDirections; ++k) {
    const double phi = 2.0 * std::numbers::pi * (double(k) + 0.5) / kDirections;
    const glm::dvec3 dir(std::cos(phi), 0, std::sin(phi));
    double lo = 0.0, hi = 20.0;  // shadowed at lo, lit at hi
    ASSERT_TRUE(shadowed(q0) && !shadowed(q0 + hi * dir));
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      (shadowed(q0 + mid * dir) ? lo : hi) = mid;
    }
    pts.add(glm::vec3(q0 + lo * (1.0 - kMargin) * dir), {0, 1, 0});
    expected.push_back(0.0f);
    pts.add(glm::vec3(q0 + lo * (1.0 + kMargin) * dir), {0, 1, 0});
    expected.push_back(1.0f);
  }

  for (const bool analytic : {true, false}) {
    sb::core::Scene s;
    s.light = point_light(glm::vec3(l));
    s.meshes.push_back(sphere(glm::vec3(c), float(r), 8, 6, analytic));
    const ref::Result res = trace(s, pts, 16);
    int wrong_inside = 0, wrong_outside = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
      const float v = res.visibility.data[i];
      if (analytic) {
        EXPECT_EQ(v, expected[i]) << "point " << i;
      }
      if (v != expected[i]) ++(expected[i] == 0.0f ? wrong_inside : wrong_outside);
    }
    if (!analytic) {
      // The inscribed polyhedron's shadow is smaller: inside points go lit,
      // outside ones never go dark.
      EXPECT_GE(wrong_inside, kDirections / 4);
      EXPECT_EQ(wrong_outside, 0);
    }
  }
}

// ---- soft shadow from below the centre, in closed form ------------------------

// A ground point directly below a sphere's centre, a square light centred
// over both and parallel to the ground. The sphere's shadow cone from the
// point is a circular cone about the vertical, half-angle asin(r / D), so on
// the light's plane (height H) it covers a disc of radius H tan(asin(r / D));
// the disc lies inside the square, so V = 1 - pi rho^2 / (2a)^2 exactly.
TEST(referenceAnalytic, SoftShadowFromBelowTheCentreMatchesTheClosedForm) {
  const double D = 2.0, r = 0.5, H = 10.0, a = 3.0;
  const double alpha = std::asin(r / D), rho = H * std::tan(alpha);
  ASSERT_LT(rho, a);
  const double exact = 1.0 - std::numbers::pi * rho * rho / (4.0 * a * a);

  Points pts;
  pts.add({0, 0, 0}, {0, 1, 0});  // the origin: a zero ray offset
  for (const bool analytic : {true, false}) {
    sb::core::Scene s;
    s.light.center = {0, float(H), 0};
    s.light.half_u = {float(a), 0, 0};
    s.light.half_v = {0, 0, float(a)};
    s.meshes.push_back(sphere({0, float(D), 0}, float(r), 8, 6, analytic));
    const ref::Result res = trace(s, pts, 256 * 256);
    const double v = res.visibility.data[0], se = res.std_error.data[0];
    if (analytic) {
      EXPECT_NEAR(v, exact, std::max(4.0 * se, 1e-3)) << "std error " << se;
    } else {  // the polyhedron hides less of the light
      EXPECT_GT(v - exact, 0.02) << "tessellated V " << v << ", exact " << exact;
    }
  }
}

// ---- a mesh's own sphere, and a neighbour's ----------------------------------

// Points on the facets of a lit tessellated sphere: some on the facet's
// interior, some right next to its vertices (which lie on the sphere). The
// sphere's own analytic shape must not occlude them (every ray starts inside
// or on it): with the light above the facet's plane, V = 1 as on the
// triangles; below it, the horizon rule gives 0. So the self-shadow follows
// the facets, not the smooth terminator: some facets with the light above
// their plane have it below the smooth sphere's tangent plane at their corners.
TEST(referenceAnalytic, OwnSphereDoesNotOccludeItsMeshsPoints) {
  const glm::vec3 c(0, 2, 0), l(2.5f, 10, 1.5f);
  const sb::core::Mesh m = sphere(c, 1.0f, 8, 6, true);
  Points pts;
  std::vector<float> expected;
  int smooth_dark = 0;  // sample points lit here, dark on the smooth sphere
  const float w[][3] = {{1.f / 3, 1.f / 3, 1.f / 3}, {0.998f, 0.001f, 0.001f},
                        {0.001f, 0.998f, 0.001f},    {0.001f, 0.001f, 0.998f},
                        {0.5f, 0.5f, 0.0f},          {0.6f, 0.2f, 0.2f}};
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                    d = m.positions[m.indices[3 * t + 2]];
    const glm::vec3 n = glm::normalize(glm::cross(b - a, d - a));
    const glm::vec3 centroid = (a + b + d) / 3.0f;
    const float facing = glm::dot(n, glm::normalize(l - centroid));
    if (std::fabs(facing) < 1e-3f) continue;  // the light (nearly) in the facet's plane
    const bool lit = facing > 0.0f;
    for (const auto& wi : w) {
      const glm::vec3 p = wi[0] * a + wi[1] * b + wi[2] * d;
      // Light above the facet's plane, below the smooth sphere's tangent
      // plane at p's radial projection.
      if (lit && glm::dot(p - c, l - p) < 0.0f) ++smooth_dark;
      pts.add(p, n);
      expected.push_back(lit ? 1.0f : 0.0f);
    }
  }
  sb::core::Scene s;
  s.light = point_light(l);
  s.meshes.push_back(m);
  const ref::Result res = trace(s, pts, 16);
  for (size_t i = 0; i < expected.size(); ++i)
    EXPECT_EQ(res.visibility.data[i], expected[i])
        << "point " << i << " at " << pts.p[i].x << ", " << pts.p[i].y << ", " << pts.p[i].z;
  EXPECT_GT(smooth_dark, 0) << "no facet where the facets and the smooth terminator differ";
}

// Sphere B (fine) under sphere A (coarse), both analytic, a near-point light
// above: A's shadow falls across B's top. Points sampled over B's lit facets
// must be occluded exactly when their segment to the light meets A's ball
// (1% margins left out), while B's own sphere occludes none of them. The
// tessellated A misses some of the points its ball covers.
TEST(referenceAnalytic, NeighbourSphereOccludesExactly) {
  const glm::vec3 ca(0, 3, 0), cb(0.9f, 1, 0), l(0, 10, 0);
  const float r = 1.0f;
  const sb::core::Mesh b_mesh = sphere(cb, r, 16, 12, true);
  Points pts;
  std::vector<float> expected;
  for (size_t t = 0; t < b_mesh.triangle_count(); ++t) {
    const glm::vec3 a = b_mesh.positions[b_mesh.indices[3 * t]],
                    b = b_mesh.positions[b_mesh.indices[3 * t + 1]],
                    d = b_mesh.positions[b_mesh.indices[3 * t + 2]];
    const glm::vec3 n = glm::normalize(glm::cross(b - a, d - a));
    if (glm::dot(n, glm::normalize(l - (a + b + d) / 3.0f)) < 1e-2f) continue;  // not lit
    for (int i = 0; i <= 4; ++i)
      for (int j = 0; i + j <= 4; ++j) {
        const float u = (float(i) + 0.25f) / 5.0f, v = (float(j) + 0.25f) / 5.0f;
        const glm::vec3 p = (1.0f - u - v) * a + u * b + v * d;
        const double dist = segment_distance(glm::dvec3(ca), glm::dvec3(p), glm::dvec3(l));
        if (std::fabs(dist - r) < 0.01 * r) continue;
        pts.add(p, n);
        expected.push_back(dist < r ? 0.0f : 1.0f);
      }
  }
  size_t dark = 0;
  for (float e : expected) dark += e == 0.0f;
  ASSERT_GT(dark, 20u);
  ASSERT_GT(expected.size() - dark, 20u);

  for (const bool analytic : {true, false}) {
    sb::core::Scene s;
    s.light = point_light(l);
    s.meshes.push_back(sphere(ca, r, 8, 6, analytic));
    s.meshes.push_back(sphere(cb, r, 16, 12, analytic));
    const ref::Result res = trace(s, pts, 16);
    int wrong = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
      if (analytic) {
        EXPECT_EQ(res.visibility.data[i], expected[i]) << "point " << i;
      }
      wrong += res.visibility.data[i] != expected[i];
    }
    if (!analytic) {
      EXPECT_GT(wrong, 0);
    }
  }
}

// ---- the scene option and the cache key ---------------------------------------

sb::core::Scene grid(bool analytic) {
  const sb::core::SceneType* t = sb::core::find_scene_type("sphere_grid");
  return t->build(sb::core::resolve_params(
      t->params, {{"grid", 2}, {"slices", 8}, {"stacks", 6}, {"analytic", analytic}}, "test",
      "/params"));
}

// The G-buffer is the triangles' whatever the option; the reference's cache
// key tells the analytic reference from the tessellated one, and follows the
// shape itself.
TEST(referenceAnalytic, CacheKeyTellsAnalyticFromTessellated) {
  const sb::core::Scene tess = grid(false), analytic = grid(true);
  EXPECT_EQ(tess.analytic_caster_count(), 0u);
  EXPECT_EQ(analytic.analytic_caster_count(), 4u);
  const ref::GBuffer gt = ref::trace_gbuffer(tess, 48, 36),
                     ga = ref::trace_gbuffer(analytic, 48, 36);
  ASSERT_EQ(gt.positions.data.size(), ga.positions.data.size());
  EXPECT_EQ(std::memcmp(gt.positions.data.data(), ga.positions.data.data(),
                        gt.positions.data.size() * sizeof(float)),
            0);
  const ref::Settings st(16, 1);
  const std::string key_tess = ref::cache_key(tess, gt.positions, gt.normals, st);
  const std::string key_analytic = ref::cache_key(analytic, gt.positions, gt.normals, st);
  EXPECT_NE(key_tess, key_analytic);
  EXPECT_EQ(key_analytic, ref::cache_key(grid(true), gt.positions, gt.normals, st));
  sb::core::Scene bigger = analytic;
  bigger.meshes[0].analytic.radius *= 1.01f;
  EXPECT_NE(ref::cache_key(bigger, gt.positions, gt.normals, st), key_analytic);
  sb::core::Scene moved = analytic;
  moved.meshes[0].analytic.center.y += 0.01f;
  EXPECT_NE(ref::cache_key(moved, gt.positions, gt.normals, st), key_analytic);

  // And the two references differ on the same points.
  const ref::Result rt = ref::compute(tess, gt.positions, gt.normals, st);
  const ref::Result ra = ref::compute(analytic, gt.positions, gt.normals, st);
  int differ = 0;
  for (size_t i = 0; i < rt.visibility.data.size(); ++i)
    differ += rt.visibility.data[i] != ra.visibility.data[i];
  EXPECT_GT(differ, 0);
}

TEST(referenceAnalytic, RejectsShapesItCannotTrace) {
  Points pts;
  pts.add({0, 0, 0}, {0, 1, 0});
  sb::core::Scene s;
  s.light = point_light({0, 10, 0});
  s.meshes.push_back(sphere({0, 2, 0}, 1.0f, 8, 6, true));
  s.meshes[0].analytic.radius = 0.0f;
  EXPECT_THROW(trace(s, pts, 1), sb::core::InputError);
  s.meshes[0].analytic.radius = std::nanf("");
  EXPECT_THROW(trace(s, pts, 1), sb::core::InputError);
  s.meshes[0].analytic.radius = 0.9f;  // the mesh pokes out: its own points could hit it
  EXPECT_THROW(trace(s, pts, 1), sb::core::InputError);
}

}  // namespace
