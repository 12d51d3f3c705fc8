#include <gtest/gtest.h>

#include <map>
#include <set>

#include "core/scene_types.h"
#include "scene_type_test_util.h"
#include "scenes/jeep.h"
#include "scenes/topology.h"

namespace sb {

using core::Bounds;
using core::Mesh;
using core::Scene;

namespace {

using test::build_scene_type;

// The jeep a caster mesh belongs to: its name up to the '/'.
std::string jeep_of(const Mesh& m) { return m.name.substr(0, m.name.find('/')); }

std::map<std::string, Bounds> jeep_bounds(const Scene& s) {
  std::map<std::string, Bounds> out;
  for (const auto& m : s.meshes)
    if (m.casts_shadow)
      for (const auto& p : m.positions) out[jeep_of(m)].extend(p);
  return out;
}

constexpr size_t kJeepTriangles = 3620;  // at the default tessellation (20)

TEST(Jeep, OneJeepHasAFewThousandTriangles) {
  const Scene s = build_scene_type("jeep", nlohmann::json::object());
  EXPECT_EQ(s.caster_triangle_count(), kJeepTriangles);
  EXPECT_GE(s.caster_triangle_count(), 2000u);
  EXPECT_LE(s.caster_triangle_count(), 5000u);
  EXPECT_EQ(s.triangle_count(), kJeepTriangles + 2u);  // + the ground quad
  size_t direct = 0;
  for (const auto& m : make_jeep("j", 20)) direct += m.triangle_count();
  EXPECT_EQ(direct, kJeepTriangles);
}

TEST(Jeep, PartsAreNamedCastersWithTheirOwnColours) {
  const Scene s = build_scene_type("jeep", {{"count", 2}});
  std::set<std::string> names;
  for (const auto& m : s.meshes) {
    if (!m.casts_shadow) {
      EXPECT_EQ(m.name, "ground");
      continue;
    }
    EXPECT_TRUE(names.insert(m.name).second) << "duplicate " << m.name;
    EXPECT_TRUE(m.name.rfind("jeep_0/", 0) == 0 || m.name.rfind("jeep_1/", 0) == 0) << m.name;
  }
  for (const char* part : {"body", "bonnet", "roll_bar", "windscreen", "bumper_front",
                           "bumper_rear", "tyre_fl", "tyre_fr", "tyre_rl", "tyre_rr", "tyre_spare",
                           "rim_fl", "rim_spare", "headlights", "seats"})
    EXPECT_TRUE(names.count(std::string("jeep_1/") + part)) << part;
  const auto find = [&](const std::string& name) {
    for (const auto& m : s.meshes)
      if (m.name == name) return m.albedo;
    return glm::vec3(-1.0f);
  };
  EXPECT_LT(find("jeep_0/tyre_fl").r, 0.15f);               // dark tyres
  EXPECT_GT(find("jeep_0/rim_fl").r, 0.4f);                 // grey rims
  EXPECT_GT(find("jeep_0/body").g, find("jeep_0/body").b);  // olive
}

TEST(Jeep, CountMultipliesCasterTriangles) {
  for (const int n : {2, 5, 32}) {
    const Scene s = build_scene_type("jeep", {{"count", n}});
    EXPECT_EQ(s.caster_triangle_count(), size_t(n) * kJeepTriangles) << n;
    EXPECT_EQ(jeep_bounds(s).size(), size_t(n));
  }
  const Scene rows = build_scene_type("jeep", {{"count", 13}, {"layout", "rows"}});
  EXPECT_EQ(rows.caster_triangle_count(), 13u * kJeepTriangles);
}

TEST(Jeep, TessellationSweepsTriangleCount) {
  const Scene coarse = build_scene_type("jeep", {{"tessellation", 8}});
  const Scene fine = build_scene_type("jeep", {{"tessellation", 40}});
  EXPECT_LT(coarse.caster_triangle_count(), kJeepTriangles);
  EXPECT_GT(fine.caster_triangle_count(), 2 * kJeepTriangles);
}

TEST(Jeep, EveryCasterIsClosed) {
  for (const int tessellation : {6, 20, 33}) {
    const Scene s = build_scene_type("jeep", {{"count", 3}, {"tessellation", tessellation}});
    for (const auto& m : s.meshes) {
      if (!m.casts_shadow) continue;
      const MeshTopology topo = analyse_topology(m);
      EXPECT_TRUE(topo.closed()) << m.name << " at tessellation " << tessellation << ": boundary "
                                 << topo.boundary_edges << ", non-manifold "
                                 << topo.nonmanifold_edges << ", inconsistent "
                                 << topo.inconsistent_edges;
      EXPECT_EQ(m.normals.size(), m.positions.size()) << m.name;
    }
  }
}

TEST(Jeep, NothingBelowTheGroundAndTheGroundUnderEverything) {
  const Scene s = build_scene_type("jeep", {{"count", 32}});
  const Bounds casters = s.caster_bounds();
  EXPECT_GE(casters.lo.y, 0.0f);
  EXPECT_LT(casters.lo.y, 0.05f);  // the tyres stand on it
  const Mesh& ground = s.meshes.back();
  ASSERT_FALSE(ground.casts_shadow);
  Bounds g;
  for (const auto& p : ground.positions) g.extend(p);
  EXPECT_EQ(g.lo.y, 0.0f);
  EXPECT_EQ(g.hi.y, 0.0f);
  EXPECT_LT(g.lo.x, casters.lo.x);
  EXPECT_LT(g.lo.z, casters.lo.z);
  EXPECT_GT(g.hi.x, casters.hi.x);
  EXPECT_GT(g.hi.z, casters.hi.z);
}

void expect_no_overlap(const Scene& s) {
  const auto b = jeep_bounds(s);
  for (auto i = b.begin(); i != b.end(); ++i)
    for (auto j = std::next(i); j != b.end(); ++j) {
      const bool apart = i->second.hi.x < j->second.lo.x || j->second.hi.x < i->second.lo.x ||
                         i->second.hi.z < j->second.lo.z || j->second.hi.z < i->second.lo.z;
      EXPECT_TRUE(apart) << i->first << " overlaps " << j->first;
    }
}

TEST(Jeep, JeepsDoNotOverlap) {
  expect_no_overlap(build_scene_type("jeep", {{"count", 32}}));
  expect_no_overlap(build_scene_type("jeep", {{"count", 32}, {"layout", "rows"}}));
  expect_no_overlap(build_scene_type("jeep", {{"count", 32}, {"seed", 0}}));
  expect_no_overlap(build_scene_type("jeep", {{"count", 32}, {"seed", 77}, {"spacing", 0.1}}));
}

TEST(Jeep, LayoutsArrangeRowsAndGrids) {
  const auto extent = [](const Scene& s) {
    const Bounds b = s.caster_bounds();
    return glm::vec2(b.hi.x - b.lo.x, b.hi.z - b.lo.z);
  };
  // 8 side by side make a wide single row; the grid of 8 is 3 wide, 3 deep.
  const glm::vec2 rows =
      extent(build_scene_type("jeep", {{"count", 8}, {"layout", "rows"}, {"seed", 0}}));
  const glm::vec2 grid = extent(build_scene_type("jeep", {{"count", 8}, {"seed", 0}}));
  EXPECT_GT(rows.x, 2.0f * grid.x);
  EXPECT_LT(rows.y, 0.5f * grid.y);
}

TEST(Jeep, SeedIsDeterministicAndZeroAligns) {
  const Scene a = build_scene_type("jeep", {{"count", 4}, {"seed", 5}});
  const Scene b = build_scene_type("jeep", {{"count", 4}, {"seed", 5}});
  const Scene c = build_scene_type("jeep", {{"count", 4}, {"seed", 6}});
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t i = 0; i < a.meshes.size(); ++i)
    EXPECT_EQ(a.meshes[i].positions, b.meshes[i].positions);
  EXPECT_NE(a.meshes[0].positions, c.meshes[0].positions);
  // Aligned: every jeep is a translated copy of the first.
  const Scene aligned = build_scene_type("jeep", {{"count", 4}, {"seed", 0}});
  const size_t parts = make_jeep("p", 20).size();
  for (size_t j = 1; j < 4; ++j) {
    const glm::vec3 shift = aligned.meshes[j * parts].positions[0] - aligned.meshes[0].positions[0];
    EXPECT_EQ(shift.y, 0.0f);
    const Mesh& first = aligned.meshes[0];
    const Mesh& other = aligned.meshes[j * parts];
    for (size_t v = 0; v < first.positions.size(); ++v)
      EXPECT_NEAR(glm::length(other.positions[v] - first.positions[v] - shift), 0.0f, 1e-4f);
  }
}

void expect_framed(const Scene& s, const std::string& what) {
  SCOPED_TRACE(what);
  const glm::mat4 vp = s.camera.projection(4.0f / 3.0f) * s.camera.view();
  for (const auto& m : s.meshes) {
    if (!m.casts_shadow) continue;
    Bounds b;
    for (const auto& p : m.positions) b.extend(p);
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 c((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y,
                        (i & 4) ? b.hi.z : b.lo.z);
      const glm::vec4 clip = vp * glm::vec4(c, 1.0f);
      ASSERT_GT(clip.w, 0.0f) << m.name;
      const glm::vec3 ndc = glm::vec3(clip) / clip.w;
      EXPECT_LE(std::fabs(ndc.x), 1.0f) << m.name;
      EXPECT_LE(std::fabs(ndc.y), 1.0f) << m.name;
      EXPECT_LE(std::fabs(ndc.z), 1.0f) << m.name;
    }
  }
  // Looking down at 35-50 degrees.
  const glm::vec3 view = glm::normalize(s.camera.target - s.camera.eye);
  const float down = glm::degrees(std::asin(-view.y));
  EXPECT_GE(down, 35.0f);
  EXPECT_LE(down, 50.0f);
  // The whole light rectangle is above every jeep, and the light aims at the set.
  const Bounds casters = s.caster_bounds();
  for (const float u : {0.0f, 1.0f})
    for (const float v : {0.0f, 1.0f}) EXPECT_GT(s.light.point(u, v).y, casters.hi.y);
  EXPECT_LT(glm::length(s.light.target - casters.center()), 1e-3f);
  // The light is outside the casters' bounding sphere (one perspective map covers them).
  EXPECT_GT(glm::length(s.light.center - casters.center()), casters.radius());
  // Every corner ray of the view reaches the ground before the far plane, inside the ground quad.
  const Mesh& ground = s.meshes.back();
  Bounds g;
  for (const auto& p : ground.positions) g.extend(p);
  const glm::mat4 inverse = glm::inverse(vp);
  for (const float x : {-1.0f, 1.0f})
    for (const float y : {-1.0f, 1.0f}) {
      const glm::vec4 far_h = inverse * glm::vec4(x, y, 1.0f, 1.0f);
      const glm::vec3 far_point = glm::vec3(far_h) / far_h.w;
      const glm::vec3 ray = far_point - s.camera.eye;
      ASSERT_LT(far_point.y, 0.0f) << "corner ray ends above the ground";
      const glm::vec3 hit = s.camera.eye + ray * (s.camera.eye.y / -ray.y);
      EXPECT_GT(hit.x, g.lo.x);
      EXPECT_LT(hit.x, g.hi.x);
      EXPECT_GT(hit.z, g.lo.z);
      EXPECT_LT(hit.z, g.hi.z);
    }
}

TEST(Jeep, LightAndCameraFrameEveryJeep) {
  for (const int n : {1, 2, 4, 7, 8, 16, 32, 100}) {
    expect_framed(build_scene_type("jeep", {{"count", n}}), "grid " + std::to_string(n));
    expect_framed(build_scene_type("jeep", {{"count", n}, {"layout", "rows"}}),
                  "rows " + std::to_string(n));
  }
  expect_framed(build_scene_type("jeep", {{"count", 9}, {"spacing", 6.0}, {"light_size", 8.0}}),
                "sparse");
}

}  // namespace
}  // namespace sb
