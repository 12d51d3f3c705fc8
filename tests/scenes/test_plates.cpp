#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/scene_types.h"
#include "scene_type_test_util.h"
#include "scenes/topology.h"

namespace sb {

using core::Bounds;
using core::find_scene_type;
using core::InputError;
using core::Mesh;
using core::Params;
using core::resolve_params;
using core::Scene;
using core::SceneType;

namespace {

using test::build_scene_type;
using test::ndc_of;

const Mesh& mesh_named(const Scene& s, const std::string& name) {
  for (const auto& m : s.meshes)
    if (m.name == name) return m;
  ADD_FAILURE() << "no mesh " << name;
  return s.meshes.front();
}

Bounds box_of(const Mesh& m) {
  Bounds b;
  for (const auto& p : m.positions) b.extend(p);
  return b;
}

// Whether the segment p→q meets the closed box b (slab test).
bool segment_hits(glm::vec3 p, glm::vec3 q, const Bounds& b) {
  float t0 = 0.0f, t1 = 1.0f;
  const glm::vec3 d = q - p;
  for (int a = 0; a < 3; ++a) {
    if (std::fabs(d[a]) < 1e-12f) {
      if (p[a] < b.lo[a] || p[a] > b.hi[a]) return false;
      continue;
    }
    float near_t = (b.lo[a] - p[a]) / d[a], far_t = (b.hi[a] - p[a]) / d[a];
    if (near_t > far_t) std::swap(near_t, far_t);
    t0 = std::max(t0, near_t);
    t1 = std::min(t1, far_t);
    if (t0 > t1) return false;
  }
  return true;
}

void expect_in_view(const Scene& s, glm::vec3 p, float limit = 1.0f) {
  const glm::vec3 ndc = ndc_of(s, p);
  EXPECT_LE(std::fabs(ndc.x), limit) << p.x << " " << p.y << " " << p.z;
  EXPECT_LE(std::fabs(ndc.y), limit) << p.x << " " << p.y << " " << p.z;
  EXPECT_LE(std::fabs(ndc.z), 1.0f) << p.x << " " << p.y << " " << p.z;
}

// Where the ray through the view's NDC point (x, y) meets the ground y = 0;
// it must do so before the far plane.
glm::vec3 ground_at(const Scene& s, float x, float y) {
  const glm::mat4 inverse = glm::inverse(s.camera.projection(4.0f / 3.0f) * s.camera.view());
  const glm::vec4 far_h = inverse * glm::vec4(x, y, 1.0f, 1.0f);
  const glm::vec3 far_point = glm::vec3(far_h) / far_h.w;
  EXPECT_LT(far_point.y, 0.0f) << "the ray at (" << x << ", " << y << ") ends above the ground";
  const glm::vec3 ray = far_point - s.camera.eye;
  return s.camera.eye + ray * (s.camera.eye.y / -ray.y);
}

// The problem the scene type's check finds, which building reports too.
std::string rejection(const nlohmann::json& given, const std::string& param) {
  const SceneType* t = find_scene_type("plates");
  const Params p = resolve_params(t->params, given, "test", "/params");
  const auto [blamed, problem] = t->check(p);
  EXPECT_EQ(blamed, param) << given.dump();
  try {
    t->build(p);
    ADD_FAILURE() << "built " << given.dump();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "/params/" + param);
    EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
  }
  return problem;
}

void expect_closed_casters_over_a_receiver(const Scene& s, size_t casters) {
  size_t caster_triangles = 0;
  for (const auto& m : s.meshes) {
    if (!m.casts_shadow) continue;
    const MeshTopology topo = analyse_topology(m);
    EXPECT_TRUE(topo.closed()) << m.name << ": boundary " << topo.boundary_edges
                               << ", non-manifold " << topo.nonmanifold_edges << ", inconsistent "
                               << topo.inconsistent_edges;
    EXPECT_EQ(m.triangle_count(), 12u) << m.name;  // a box
    EXPECT_EQ(m.normals.size(), m.positions.size()) << m.name;
    caster_triangles += m.triangle_count();
  }
  EXPECT_EQ(caster_triangles, 12u * casters);
  EXPECT_EQ(s.caster_triangle_count(), 12u * casters);
  EXPECT_EQ(s.triangle_count(), 12u * casters + 2u);  // + the ground quad
  const Mesh& ground = mesh_named(s, "ground");
  EXPECT_FALSE(ground.casts_shadow);
  EXPECT_EQ(ground.triangle_count(), 2u);
  const Bounds g = box_of(ground);
  EXPECT_EQ(g.lo.y, 0.0f);
  EXPECT_EQ(g.hi.y, 0.0f);
  const Bounds c = s.caster_bounds();
  EXPECT_GT(c.lo.y, 0.0f);  // the plates float
  EXPECT_LT(g.lo.x, c.lo.x);
  EXPECT_LT(g.lo.z, c.lo.z);
  EXPECT_GT(g.hi.x, c.hi.x);
  EXPECT_GT(g.hi.z, c.hi.z);
}

// The light faces straight down from above every plate, outside the casters'
// bounding sphere (one perspective shadow map covers them), and every corner
// ray of the view meets the ground inside the quad before the far plane.
void expect_light_and_view(const Scene& s) {
  const glm::vec3 dir = s.light.direction();
  EXPECT_NEAR(dir.x, 0.0f, 1e-6f);
  EXPECT_NEAR(dir.z, 0.0f, 1e-6f);
  EXPECT_LT(dir.y, 0.0f);
  EXPECT_NEAR(s.light.width(), s.light.height(), 1e-5f);
  const Bounds c = s.caster_bounds();
  for (const float u : {0.0f, 1.0f})
    for (const float v : {0.0f, 1.0f}) EXPECT_GT(s.light.point(u, v).y, c.hi.y);
  EXPECT_GT(glm::length(s.light.center - c.center()), 1.05f * c.radius());
  const Bounds g = box_of(mesh_named(s, "ground"));
  for (const float x : {-1.0f, 1.0f})
    for (const float y : {-1.0f, 1.0f}) {
      const glm::vec3 hit = ground_at(s, x, y);
      EXPECT_GT(hit.x, g.lo.x);
      EXPECT_LT(hit.x, g.hi.x);
      EXPECT_GT(hit.z, g.lo.z);
      EXPECT_LT(hit.z, g.hi.z);
    }
}

TEST(Plates, EdgeIsOneClosedPlateOverAReceiver) {
  const Scene s = build_scene_type("plates", nlohmann::json::object());
  EXPECT_EQ(s.meshes.size(), 2u);
  expect_closed_casters_over_a_receiver(s, 1);
  const Bounds plate = box_of(mesh_named(s, "plate"));
  EXPECT_FLOAT_EQ(plate.hi.x, 0.0f);  // the straight edge, along z at x = 0
  EXPECT_NEAR(plate.hi.y - plate.lo.y, 0.05f, 1e-6f);
  EXPECT_NEAR(0.5f * (plate.hi.y + plate.lo.y), 1.0f, 1e-6f);
  expect_light_and_view(s);
}

TEST(Plates, StackedIsTwoClosedPlatesOverAReceiver) {
  const Scene s = build_scene_type("plates", {{"layout", "stacked"}});
  EXPECT_EQ(s.meshes.size(), 3u);
  expect_closed_casters_over_a_receiver(s, 2);
  const Bounds lower = box_of(mesh_named(s, "lower_plate"));
  const Bounds upper = box_of(mesh_named(s, "upper_plate"));
  EXPECT_NEAR(0.5f * (lower.hi.y + lower.lo.y), 1.0f, 1e-6f);
  EXPECT_NEAR(0.5f * (upper.hi.y + upper.lo.y), 4.0f, 1e-6f);
  // Seen from the light's centre the upper edge lies over the lower plate.
  const glm::vec3 l = s.light.center;
  const float y = lower.hi.y;
  const float edge_on_lower = l.x + (upper.hi.x - l.x) * (l.y - y) / (l.y - upper.hi.y);
  EXPECT_GT(edge_on_lower, lower.lo.x);
  EXPECT_LT(edge_on_lower, lower.hi.x);
  // The upper plate is the smaller one.
  EXPECT_LT(upper.hi.x - upper.lo.x, lower.hi.x - lower.lo.x);
  expect_light_and_view(s);
}

TEST(Plates, RejectsPlatesThatTouchOrStandAboveTheLight) {
  for (const double upper : {1.0, 0.5, 1.04}) {
    const std::string m =
        rejection({{"layout", "stacked"}, {"upper_height", upper}}, "upper_height");
    EXPECT_NE(m.find("expected a number greater than height + thickness (1.05)"), std::string::npos)
        << m;
  }
  EXPECT_EQ(rejection({{"layout", "stacked"}, {"upper_height", 0.5}}, "upper_height"),
            "expected a number greater than height + thickness (1.05) with layout \"stacked\" "
            "(the plates may not touch), found 0.5");
  // The edge layout has no upper plate.
  EXPECT_TRUE(find_scene_type("plates")
                  ->check(resolve_params(find_scene_type("plates")->params, {{"upper_height", 0.5}},
                                         "test", "/params"))
                  .second.empty());
  EXPECT_NO_THROW(build_scene_type("plates", {{"upper_height", 0.5}}));
  EXPECT_NE(rejection({{"height", 0.02}}, "height").find("thickness / 2 (0.025)"),
            std::string::npos);
  EXPECT_NE(rejection({{"layout", "stacked"}, {"light_height", 4.0}}, "light_height")
                .find("the top of the highest plate (4.025), found 4"),
            std::string::npos);
  EXPECT_NE(rejection({{"light_height", 1.0}}, "light_height").find("(1.025), found 1"),
            std::string::npos);
}

// The ground interval [umbra end, lit start] of the penumbra of the plate's
// edge, by similar triangles from the light's two extreme x through the top
// of the edge.
glm::vec2 penumbra_of_edge(const Scene& s) {
  const Bounds plate = box_of(mesh_named(s, "plate"));
  const glm::vec2 edge(plate.hi.x, plate.hi.y);
  float nearest = -1e30f, farthest = 1e30f, light_y = 0.0f;
  for (const float u : {0.0f, 1.0f})
    for (const float v : {0.0f, 1.0f}) {
      const glm::vec3 p = s.light.point(u, v);
      nearest = std::max(nearest, p.x);
      farthest = std::min(farthest, p.x);
      light_y = p.y;
    }
  const auto through_edge = [&](float light_x) {
    return light_x + (edge.x - light_x) * light_y / (light_y - edge.y);
  };
  return {through_edge(nearest), through_edge(farthest)};
}

TEST(Plates, EdgePenumbraMatchesSimilarTriangles) {
  // e = 1.025, k = e / (8 − e), light centred at x = −3: [2.5k, 3.5k] and [1.5k, 4.5k].
  const float k = 1.025f / (8.0f - 1.025f);
  const glm::vec2 one = penumbra_of_edge(build_scene_type("plates", {{"light_size", 1.0}}));
  EXPECT_NEAR(one.x, 2.5f * k, 1e-5f);
  EXPECT_NEAR(one.y, 3.5f * k, 1e-5f);
  EXPECT_NEAR(one.x, 0.3674f, 1e-4f);
  EXPECT_NEAR(one.y, 0.5143f, 1e-4f);
  const glm::vec2 three = penumbra_of_edge(build_scene_type("plates", {{"light_size", 3.0}}));
  EXPECT_NEAR(three.x, 1.5f * k, 1e-5f);
  EXPECT_NEAR(three.y, 4.5f * k, 1e-5f);
}

TEST(Plates, LightAndCameraStayPutForLightSizesUpToThree) {
  const Scene base = build_scene_type("plates", nlohmann::json::object());
  for (const double size : {0.0, 0.5, 2.0, 3.0}) {
    const Scene s = build_scene_type("plates", {{"light_size", size}});
    EXPECT_EQ(s.light.center, base.light.center) << size;
    EXPECT_EQ(s.camera.eye, base.camera.eye) << size;
    EXPECT_EQ(s.camera.target, base.camera.target) << size;
    EXPECT_EQ(s.meshes[0].positions, base.meshes[0].positions) << size;
  }
}

void expect_penumbra_seen(const Scene& s, float min_ndc_width) {
  const Bounds plate = box_of(mesh_named(s, "plate"));
  const glm::vec2 pen = penumbra_of_edge(s);
  ASSERT_GT(pen.x, plate.hi.x);  // on open ground, not under the plate
  // Rows across most of the image height cross the whole penumbra.
  for (const float row : {-0.8f, 0.0f, 0.8f}) {
    const float z = ground_at(s, 0.0f, row).z;
    ASSERT_GT(z, plate.lo.z + 0.5f);  // the edge is straight here
    ASSERT_LT(z, plate.hi.z - 0.5f);
    const glm::vec3 a(pen.x, 0.0f, z), b(pen.y, 0.0f, z);
    for (const glm::vec3& g : {a, b}) {
      expect_in_view(s, g, 0.95f);
      EXPECT_FALSE(segment_hits(s.camera.eye, g, plate)) << "hidden by the plate: " << g.x;
    }
    EXPECT_GT(ndc_of(s, b).x - ndc_of(s, a).x, min_ndc_width) << row;
    // The shadow edge runs along the image's vertical centre line.
    EXPECT_NEAR(ndc_of(s, 0.5f * (a + b)).x, 0.0f, 1e-3f) << row;
  }
  // The straight edge spans the whole view: every corner of it sees ground
  // alongside the plate's straight edge, well inside its ends.
  for (const float x : {-1.0f, 1.0f})
    for (const float y : {-1.0f, 1.0f}) {
      const float z = ground_at(s, x, y).z;
      EXPECT_GT(z, plate.lo.z + 0.5f);
      EXPECT_LT(z, plate.hi.z - 0.5f);
    }
}

TEST(Plates, EdgePenumbraIsInViewAndUnblocked) {
  {
    SCOPED_TRACE("light_size 1");
    expect_penumbra_seen(build_scene_type("plates", {{"light_size", 1.0}}), 0.08f);
  }
  {
    SCOPED_TRACE("light_size 3");
    expect_penumbra_seen(build_scene_type("plates", {{"light_size", 3.0}}), 0.25f);
  }
  for (const double height : {0.3, 2.5}) {
    SCOPED_TRACE("height " + std::to_string(height));
    const Scene s = build_scene_type("plates", {{"light_size", 3.0}, {"height", height}});
    expect_penumbra_seen(s, 0.25f);
    expect_light_and_view(s);
  }
  {
    SCOPED_TRACE("light_size 6, light_height 5");
    const Scene s = build_scene_type("plates", {{"light_size", 6.0}, {"light_height", 5.0}});
    expect_penumbra_seen(s, 0.25f);
    expect_light_and_view(s);
  }
}

// The ground point where, seen from the light's centre, the upper plate's
// edge projects: in the lower plate's umbra for the whole light, and seen by
// the camera under the lower plate.
void expect_bleeding_line_seen(const Scene& s) {
  const Bounds lower = box_of(mesh_named(s, "lower_plate"));
  const Bounds upper = box_of(mesh_named(s, "upper_plate"));
  const glm::vec3 l = s.light.center;
  const glm::vec3 edge(upper.hi.x, 0.5f * (upper.lo.y + upper.hi.y), 0.0f);
  const glm::vec3 line = l + (edge - l) * (l.y / (l.y - edge.y));
  ASSERT_NEAR(line.y, 0.0f, 1e-5f);
  for (const float z : {-1.0f, 0.0f, 1.0f}) {
    const glm::vec3 g(line.x, 0.0f, z);
    ASSERT_GT(g.x, lower.lo.x);  // under the lower plate
    ASSERT_LT(g.x, lower.hi.x);
    for (const float u : {0.0f, 1.0f})
      for (const float v : {0.0f, 1.0f})
        EXPECT_TRUE(segment_hits(g, s.light.point(u, v), lower))
            << "light corner (" << u << ", " << v << ") reaches " << g.x << ", " << z;
    EXPECT_FALSE(segment_hits(s.camera.eye, g, lower)) << "hidden by the lower plate at z " << z;
    EXPECT_FALSE(segment_hits(s.camera.eye, g, upper)) << "hidden by the upper plate at z " << z;
    expect_in_view(s, g, 0.9f);
  }
  // Ground on both sides of the line, under the lower plate, is seen too.
  for (const float dx : {-0.3f, 0.3f}) {
    const glm::vec3 g(line.x + dx, 0.0f, 0.0f);
    EXPECT_FALSE(segment_hits(s.camera.eye, g, lower)) << dx;
    expect_in_view(s, g);
  }
}

TEST(Plates, StackedBleedingLineIsInUmbraAndInView) {
  for (const double size : {0.0, 1.0, 3.0}) {
    SCOPED_TRACE("light_size " + std::to_string(size));
    expect_bleeding_line_seen(
        build_scene_type("plates", {{"layout", "stacked"}, {"light_size", size}}));
  }
  for (const auto& [height, upper] : {std::pair{0.3, 2.0}, {1.0, 6.0}, {2.0, 5.0}}) {
    SCOPED_TRACE("height " + std::to_string(height) + ", upper " + std::to_string(upper));
    const Scene s = build_scene_type(
        "plates", {{"layout", "stacked"}, {"height", height}, {"upper_height", upper}});
    expect_bleeding_line_seen(s);
    expect_light_and_view(s);
  }
}

}  // namespace
}  // namespace sb
