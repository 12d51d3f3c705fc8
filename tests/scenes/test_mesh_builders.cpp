#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>

#include "scenes/mesh_builders.h"
#include "scenes/topology.h"

namespace sb {

using core::AnalyticShape;
using core::Bounds;
using core::Mesh;

namespace {

glm::vec3 corner(const Mesh& m, size_t t, int k) { return m.positions[m.indices[3 * t + k]]; }

glm::vec3 face_normal(const Mesh& m, size_t t) {
  const glm::vec3 a = corner(m, t, 0), b = corner(m, t, 1), c = corner(m, t, 2);
  return glm::cross(b - a, c - a);
}

glm::vec3 centroid(const Mesh& m, size_t t) {
  return (corner(m, t, 0) + corner(m, t, 1) + corner(m, t, 2)) / 3.0f;
}

Bounds bounds_of(const Mesh& m) {
  Bounds b;
  for (const auto& p : m.positions) b.extend(p);
  return b;
}

// For a convex solid every face points away from an interior point.
void expect_outward_from(const Mesh& m, glm::vec3 inside) {
  for (size_t t = 0; t < m.triangle_count(); ++t)
    EXPECT_GT(glm::dot(face_normal(m, t), centroid(m, t) - inside), 0.0f)
        << m.name << " triangle " << t;
}

// Vertex normals are unit length and on the same side as their faces.
void expect_normals_agree(const Mesh& m) {
  ASSERT_EQ(m.normals.size(), m.positions.size());
  for (size_t t = 0; t < m.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 n = m.normals[m.indices[3 * t + size_t(k)]];
      EXPECT_NEAR(glm::length(n), 1.0f, 1e-4f);
      EXPECT_GT(glm::dot(n, face_normal(m, t)), 0.0f) << m.name << " triangle " << t;
    }
}

void expect_closed(const Mesh& m) {
  const MeshTopology topo = analyse_topology(m);
  EXPECT_TRUE(topo.closed()) << m.name << ": boundary " << topo.boundary_edges << ", non-manifold "
                             << topo.nonmanifold_edges << ", inconsistent "
                             << topo.inconsistent_edges;
}

TEST(MakeBox, ClosedOutwardWithExactBounds) {
  const glm::vec3 c(1.0f, -2.0f, 0.5f), h(0.3f, 1.7f, 0.05f);
  const Mesh m = make_box("box", c, h);
  EXPECT_EQ(m.name, "box");
  EXPECT_EQ(m.triangle_count(), 12u);
  EXPECT_EQ(m.positions.size(), 24u);  // flat faces: every corner three times
  expect_closed(m);
  expect_outward_from(m, c);
  expect_normals_agree(m);
  const Bounds b = bounds_of(m);
  EXPECT_EQ(b.lo, c - h);
  EXPECT_EQ(b.hi, c + h);
}

TEST(MakeBox, RotatedStaysClosedAndOutward) {
  for (const glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0.3f, 1.0f, -0.4f)})
    for (const float degrees : {10.0f, 45.0f, 137.0f}) {
      const glm::mat3 r(glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::normalize(axis)));
      const glm::vec3 c(0.0f, 3.0f, -1.0f), h(0.72f, 0.03f, 0.025f);
      const Mesh m = make_box("rotated", c, h, r);
      expect_closed(m);
      expect_outward_from(m, c);
      expect_normals_agree(m);
      for (const auto& p : m.positions) EXPECT_NEAR(glm::length(p - c), glm::length(h), 1e-5f);
    }
}

struct CylinderCase {
  glm::vec3 base;
  glm::vec3 axis;
  float r0, r1, height;
  int segments;
};

TEST(MakeCylinder, ClosedOutwardAndBoundedForManyShapes) {
  const CylinderCase cases[] = {
      {{0, 0, 0}, {0, 1, 0}, 0.5f, 0.5f, 2.0f, 16},             // upright
      {{1, 2, 3}, {1, 0, 0}, 0.2f, 0.2f, 0.18f, 20},            // a rim: short, along x
      {{0, 0, 0}, {-1, 0, 0}, 0.05f, 0.05f, 1.2f, 3},           // triangular prism, -x
      {{0, 0.5f, 0}, {0, 1, 0}, 0.3f, 0.21f, 1.5f, 8},          // tapered trunk
      {{2, 1, -1}, {0.6f, 0.7f, -0.2f}, 0.1f, 0.07f, 0.9f, 7},  // tilted tapered branch
      {{0, 0, 0}, {0, -1, 0}, 0.1f, 0.4f, 0.5f, 12},            // widening, pointing down
      {{0, 0, 0}, {0.2f, 0.1f, 1.0f}, 0.4f, 0.0f, 1.0f, 10},    // cone, apex on top
      {{0, 0, 0}, {1, 1, 1}, 0.0f, 0.4f, 1.0f, 5},              // cone, apex at the base
  };
  for (const auto& k : cases) {
    const Mesh m = make_cylinder("cyl", k.base, k.axis, k.r0, k.r1, k.height, k.segments);
    SCOPED_TRACE("segments " + std::to_string(k.segments) + " r " + std::to_string(k.r0) + "/" +
                 std::to_string(k.r1));
    const size_t s = size_t(k.segments);
    const size_t apexes = size_t(k.r0 == 0.0f) + size_t(k.r1 == 0.0f);
    EXPECT_EQ(m.triangle_count(),
              4 * s - 2 * apexes * s);  // an apex has no cap and single side triangles
    expect_closed(m);
    const glm::vec3 w = glm::normalize(k.axis);
    expect_outward_from(m, k.base + 0.5f * k.height * w);
    expect_normals_agree(m);
    // Every vertex within the frustum: along the axis in [0, h], radius linear in between.
    for (const auto& p : m.positions) {
      const float along = glm::dot(p - k.base, w);
      EXPECT_GE(along, -1e-5f);
      EXPECT_LE(along, k.height + 1e-5f);
      const float radial = glm::length(p - k.base - along * w);
      const float allowed = k.r0 + (k.r1 - k.r0) * along / k.height;
      EXPECT_LE(radial, allowed + 1e-5f);
    }
  }
}

TEST(MakeCylinder, UprightBoundsAndCapNormals) {
  const Mesh m = make_cylinder("c", {0, 1, 0}, {0, 1, 0}, 0.5f, 0.5f, 2.0f, 32);
  const Bounds b = bounds_of(m);
  EXPECT_NEAR(b.lo.y, 1.0f, 1e-6f);
  EXPECT_NEAR(b.hi.y, 3.0f, 1e-6f);
  EXPECT_NEAR(b.hi.x, 0.5f, 1e-6f);
  EXPECT_NEAR(b.lo.x, -0.5f, 1e-6f);
  EXPECT_NEAR(b.hi.z, 0.5f, 1e-2f);  // 32 segments: the ring reaches z = ±0.5 exactly or nearly
  size_t up = 0, down = 0;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const glm::vec3 n = glm::normalize(face_normal(m, t));
    up += n.y > 0.999f;
    down += n.y < -0.999f;
  }
  EXPECT_EQ(up, 32u);
  EXPECT_EQ(down, 32u);
}

TEST(MakeCylinder, TaperedSideNormalsLeanTowardsTheNarrowEnd) {
  const Mesh m = make_cylinder("t", {0, 0, 0}, {0, 1, 0}, 0.4f, 0.2f, 1.0f, 12);
  // Side vertices (not on a cap) have normals tilted up by atan(0.2 / 1).
  const float expected = 0.2f / std::sqrt(1.0f + 0.04f);
  size_t side = 0;
  for (const auto& n : m.normals)
    if (std::fabs(n.y) < 0.99f) {
      EXPECT_NEAR(n.y, expected, 1e-5f);
      ++side;
    }
  EXPECT_EQ(side, 4u * 12u);
}

TEST(MakeTorus, ClosedOutwardFromTheCoreCircle) {
  struct Case {
    glm::vec3 center, axis;
    float major, minor;
    int sm, sn;
  };
  const Case cases[] = {{{0, 0.385f, 1}, {1, 0, 0}, 0.255f, 0.125f, 20, 10},
                        {{1, 2, 3}, {0, 0.7f, -0.7f}, 0.18f, 0.018f, 16, 3},
                        {{0, 0, 0}, {0, 1, 0}, 1.0f, 0.5f, 8, 6},
                        {{-2, 1, 0}, {0.1f, -0.3f, 0.9f}, 2.0f, 0.1f, 64, 24}};
  for (const auto& k : cases) {
    const Mesh m = make_torus("torus", k.center, k.axis, k.major, k.minor, k.sm, k.sn);
    EXPECT_EQ(m.triangle_count(), 2u * size_t(k.sm) * size_t(k.sn));
    expect_closed(m);
    expect_normals_agree(m);
    const glm::vec3 w = glm::normalize(k.axis);
    const auto core = [&](glm::vec3 p) {  // nearest point on the tube's centre circle
      const glm::vec3 rel = p - k.center;
      return k.center + k.major * glm::normalize(rel - glm::dot(rel, w) * w);
    };
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      const glm::vec3 c = centroid(m, t);
      EXPECT_GT(glm::dot(face_normal(m, t), c - core(c)), 0.0f) << "triangle " << t;
    }
    for (const auto& p : m.positions) EXPECT_NEAR(glm::length(p - core(p)), k.minor, 1e-5f);
  }
}

TEST(MakeTorus, AxisAlignedBounds) {
  const Mesh m = make_torus("tyre", {0, 1, 0}, {1, 0, 0}, 0.3f, 0.1f, 24, 12);
  const Bounds b = bounds_of(m);
  EXPECT_NEAR(b.lo.x, -0.1f, 1e-5f);
  EXPECT_NEAR(b.hi.x, 0.1f, 1e-5f);
  EXPECT_NEAR(b.lo.y, 0.6f, 1e-2f);
  EXPECT_NEAR(b.hi.y, 1.4f, 1e-2f);
  EXPECT_GE(b.lo.y, 0.6f - 1e-5f);
  EXPECT_LE(b.hi.z, 0.4f + 1e-5f);
}

TEST(TransformMesh, MovesPositionsAndNormalsAndKeepsWindingUnderMirrors) {
  const Mesh box = make_box("b", {0, 0, 0}, {1.0f, 0.5f, 0.25f});
  const glm::mat4 rotate =
      glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(5, 1, -2)), 0.7f, glm::vec3(0, 1, 0));
  const glm::mat4 mirror = glm::scale(rotate, glm::vec3(-1.0f, 2.0f, 1.0f));
  for (const glm::mat4& t : {rotate, mirror}) {
    Mesh m = box;
    transform_mesh(m, t);
    expect_closed(m);
    expect_outward_from(m, glm::vec3(5, 1, -2));
    expect_normals_agree(m);
    for (size_t i = 0; i < m.positions.size(); ++i) {
      const glm::vec3 expected(t * glm::vec4(box.positions[i], 1.0f));
      EXPECT_NEAR(glm::length(m.positions[i] - expected), 0.0f, 1e-5f);
    }
  }
}

TEST(TransformMesh, MovesAnAnalyticSphereUnderSimilaritiesOnly) {
  Mesh m = make_box("b", {0, 0, 0}, {1.0f, 1.0f, 1.0f});
  m.analytic = AnalyticShape::sphere({1, 2, 3}, 2.0f);
  const glm::mat4 t = glm::scale(
      glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(5, 1, -2)), 0.7f, glm::vec3(0, 1, 0)),
      glm::vec3(-1.5f, 1.5f, 1.5f));
  Mesh moved = m;
  transform_mesh(moved, t);
  EXPECT_NEAR(glm::distance(moved.analytic.center, glm::vec3(t * glm::vec4(1, 2, 3, 1))), 0.0f,
              1e-5f);
  EXPECT_NEAR(moved.analytic.radius, 3.0f, 1e-5f);
  Mesh squashed = m;
  EXPECT_THROW(transform_mesh(squashed, glm::scale(glm::mat4(1.0f), glm::vec3(1, 0.5f, 1))),
               std::invalid_argument);
  Mesh other = make_box("c", {4, 0, 0}, {1.0f, 1.0f, 1.0f});
  EXPECT_THROW(append_mesh(other, m), std::invalid_argument);
}

TEST(AppendMesh, MergesDisjointClosedPartsIntoAClosedMesh) {
  Mesh m = make_box("parts", {0, 0, 0}, {0.5f, 0.5f, 0.5f});
  m.albedo = glm::vec3(0.1f, 0.2f, 0.3f);
  append_mesh(m, make_cylinder("c", {2, 0, 0}, {0, 1, 0}, 0.3f, 0.2f, 1.0f, 9));
  append_mesh(m, make_torus("t", {0, 0.45f, 0}, {0, 1, 0}, 0.6f, 0.1f, 12, 6));  // overlapping
  EXPECT_EQ(m.name, "parts");
  EXPECT_EQ(m.albedo, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(m.triangle_count(), 12u + 36u + 144u);
  EXPECT_EQ(m.normals.size(), m.positions.size());
  EXPECT_TRUE(m.uvs.empty());
  for (const uint32_t i : m.indices) EXPECT_LT(i, m.positions.size());
  expect_closed(m);
  expect_normals_agree(m);
}

TEST(AppendMesh, KeepsTextureCoordinatesPerVertex) {
  Mesh textured = make_box("t", {0, 0, 0}, {1, 1, 1});
  textured.uvs.assign(textured.positions.size(), glm::vec2(0.5f));
  Mesh m = make_box("m", {3, 0, 0}, {1, 1, 1});
  append_mesh(m, textured);
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  EXPECT_EQ(m.uvs.front(), glm::vec2(0.0f));
  EXPECT_EQ(m.uvs.back(), glm::vec2(0.5f));
}

TEST(MeshBuilders, RejectDegenerateInput) {
  EXPECT_THROW(make_box("b", {0, 0, 0}, {1, 0, 1}), std::invalid_argument);
  EXPECT_THROW(make_cylinder("c", {0, 0, 0}, {0, 1, 0}, 1, 1, 1, 2), std::invalid_argument);
  EXPECT_THROW(make_cylinder("c", {0, 0, 0}, {0, 0, 0}, 1, 1, 1, 8), std::invalid_argument);
  EXPECT_THROW(make_cylinder("c", {0, 0, 0}, {0, 1, 0}, 0, 0, 1, 8), std::invalid_argument);
  EXPECT_THROW(make_cylinder("c", {0, 0, 0}, {0, 1, 0}, 1, 1, 0, 8), std::invalid_argument);
  EXPECT_THROW(make_torus("t", {0, 0, 0}, {0, 1, 0}, 0.1f, 0.2f, 8, 8), std::invalid_argument);
  EXPECT_THROW(make_torus("t", {0, 0, 0}, {0, 1, 0}, 1, 0.2f, 8, 2), std::invalid_argument);
}

}  // namespace
}  // namespace sb
