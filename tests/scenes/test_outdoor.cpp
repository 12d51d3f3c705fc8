// The `outdoor` scene (scenes/outdoor.cpp): a kilometre of ground under the
// sun, seen from a pedestrian's eye, its layout from a seed and densities.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/scene_types.h"
#include "scene_type_test_util.h"
#include "scenes/leaf.h"
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

using nlohmann::json;
using test::build_scene_type;

// Throws when the type is missing, which gtest reports as the test's failure.
Scene outdoor(const json& given = json::object()) {
  if (find_scene_type("outdoor") == nullptr) throw std::runtime_error("no scene type 'outdoor'");
  return build_scene_type("outdoor", given);
}

const Mesh* find_mesh(const Scene& s, const std::string& name) {
  for (const Mesh& m : s.meshes)
    if (m.name == name) return &m;
  return nullptr;
}

// Triangles of the meshes whose name starts with `prefix`.
size_t triangles_of(const Scene& s, const std::string& prefix) {
  size_t n = 0;
  for (const Mesh& m : s.meshes)
    if (m.name.rfind(prefix, 0) == 0) n += m.triangle_count();
  return n;
}

template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  // memcmp must not see the null data() of an empty vector (UBSan).
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

Bounds receiver_bounds(const Scene& s) {
  Bounds b;
  for (const Mesh& m : s.meshes)
    if (!m.casts_shadow)
      for (const glm::vec3& p : m.positions) b.extend(p);
  return b;
}

TEST(OutdoorScene, SameSeedSameBytesOtherSeedOtherLayout) {
  const Scene a = outdoor({{"seed", 7}}), b = outdoor({{"seed", 7}}), c = outdoor({{"seed", 8}});
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    const Mesh &x = a.meshes[i], &y = b.meshes[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_TRUE(same_bytes(x.positions, y.positions)) << x.name;
    EXPECT_TRUE(same_bytes(x.normals, y.normals)) << x.name;
    EXPECT_TRUE(same_bytes(x.uvs, y.uvs)) << x.name;
    EXPECT_TRUE(same_bytes(x.indices, y.indices)) << x.name;
  }
  ASSERT_EQ(a.textures.size(), 1u);
  EXPECT_EQ(a.textures[0].rgba, b.textures[0].rgba);
  for (const std::string name : {"buildings_1", "trees/wood", "leaves", "poles"}) {
    ASSERT_NE(find_mesh(a, name), nullptr) << name;
    ASSERT_NE(find_mesh(c, name), nullptr) << name;
    EXPECT_FALSE(same_bytes(find_mesh(a, name)->positions, find_mesh(c, name)->positions)) << name;
  }
}

TEST(OutdoorScene, TheGroundIsAFlatReceiverSpanningTheExtent) {
  for (const double extent : {1000.0, 1600.0}) {
    const Scene s = outdoor({{"extent", extent}});
    const Bounds g = receiver_bounds(s);
    EXPECT_GE(g.hi.x - g.lo.x, float(extent));
    EXPECT_GE(g.hi.z - g.lo.z, float(extent));
    EXPECT_EQ(g.lo.y, 0.0f);
    EXPECT_EQ(g.hi.y, 0.0f);
    ASSERT_NE(find_mesh(s, "ground"), nullptr);
    ASSERT_NE(find_mesh(s, "road"), nullptr);
    EXPECT_FALSE(find_mesh(s, "ground")->casts_shadow);
    EXPECT_FALSE(find_mesh(s, "road")->casts_shadow);
  }
}

TEST(OutdoorScene, EveryCasterStandsOnTheGroundFromTheCamerasFeetToTheFarEnd) {
  const Scene s = outdoor();
  const glm::vec2 eye(s.camera.eye.x, s.camera.eye.z);
  float nearest = 1e30f, farthest = 0.0f, tallest = 0.0f;
  for (const Mesh& m : s.meshes) {
    if (!m.casts_shadow) continue;
    for (const glm::vec3& p : m.positions) {
      EXPECT_GE(p.y, 0.0f) << m.name;
      const float d = glm::length(glm::vec2(p.x, p.z) - eye);
      nearest = std::min(nearest, d);
      farthest = std::max(farthest, d);
      tallest = std::max(tallest, p.y);
    }
  }
  EXPECT_LT(nearest, 2.0f);     // the near field: a bollard beside the camera
  EXPECT_GT(farthest, 900.0f);  // content to the far end of a 1 km ground
  EXPECT_GT(tallest, 20.0f);    // and tens of metres high
  // Buildings, wood and poles are closed; the casters' parts are in
  // contact with the ground (the lowest caster vertex at y = 0).
  EXPECT_EQ(s.caster_bounds().lo.y, 0.0f);
  for (const Mesh& m : s.meshes)
    if (m.casts_shadow && !m.alpha_tested()) {
      EXPECT_TRUE(analyse_topology(m).closed()) << m.name;
    }
}

TEST(OutdoorScene, TreesCarryAlphaMaskedDoubleSidedLeaves) {
  const Scene s = outdoor({{"leaves", 50}});
  const Mesh* leaves = find_mesh(s, "leaves");
  ASSERT_NE(leaves, nullptr);
  EXPECT_TRUE(leaves->alpha_tested());
  EXPECT_TRUE(leaves->double_sided);
  EXPECT_TRUE(leaves->casts_shadow);
  EXPECT_EQ(leaves->uvs.size(), leaves->positions.size());
  ASSERT_EQ(leaves->base_color_texture, 0);
  const double opaque = opaque_fraction(s.textures[0], leaves->alpha_cutoff);
  EXPECT_GT(opaque, 0.2);  // a mask with holes, not a solid quad
  EXPECT_LT(opaque, 0.8);
  // 50 leaves of two triangles per tree, every tree with its wood.
  const size_t trees = find_mesh(s, "trees/wood")->triangle_count() / (4 * 6 + 3 * 4 * 5);
  EXPECT_GT(trees, 100u);
  EXPECT_EQ(leaves->triangle_count(), trees * 50 * 2);
}

TEST(OutdoorScene, ThePedestriansCameraLooksAlongTheGroundToItsFarEnd) {
  for (const double extent : {1000.0, 3000.0}) {
    const Scene s = outdoor({{"extent", extent}});
    const core::Camera& c = s.camera;
    EXPECT_GT(c.eye.y, 1.0f);
    EXPECT_LE(c.eye.y, 2.5f);
    const glm::vec3 view = glm::normalize(c.target - c.eye);
    EXPECT_LT(std::fabs(view.y), std::sin(glm::radians(10.0f)));
    EXPECT_GE(c.near_plane, 0.1f);
    EXPECT_LE(c.near_plane, 0.5f);
    // Every corner of the ground (and 100 m above it) lies before the far plane.
    const Bounds g = receiver_bounds(s);
    for (const float x : {g.lo.x, g.hi.x})
      for (const float z : {g.lo.z, g.hi.z})
        EXPECT_LT(glm::dot(glm::vec3(x, 100.0f, z) - c.eye, view), c.far_plane) << x << " " << z;
    // The ground ahead reaches at least the extent along the view.
    EXPECT_GE(glm::dot(glm::vec3(c.eye.x, 0.0f, g.lo.z) - c.eye, view), 0.98f * float(extent));
  }
}

TEST(OutdoorScene, TheLightIsTheSunAtTheGivenElevationAndDiameter) {
  const Scene s = outdoor();
  EXPECT_TRUE(s.light.is_sun());
  EXPECT_NEAR(s.light.angular_diameter, glm::radians(core::kSunDiameterDegrees), 1e-7f);
  EXPECT_NEAR(s.light.to_sun().y, std::sin(glm::radians(35.0f)), 1e-5f);
  const Scene t = outdoor({{"sun_elevation", 60}, {"sun_diameter", 2}, {"sun_azimuth", 90}});
  EXPECT_TRUE(t.light.is_sun());
  EXPECT_NEAR(t.light.angular_diameter, glm::radians(2.0f), 1e-7f);
  EXPECT_NEAR(t.light.to_sun().y, std::sin(glm::radians(60.0f)), 1e-5f);
  // Azimuth 90: to the right of the view (+x), level with it.
  EXPECT_NEAR(t.light.to_sun().x, std::cos(glm::radians(60.0f)), 1e-5f);
  EXPECT_NEAR(t.light.to_sun().z, 0.0f, 1e-5f);
}

// The positions of the meshes whose name starts with `prefix`, one after another.
std::vector<glm::vec3> positions_of(const Scene& s, const std::string& prefix) {
  std::vector<glm::vec3> all;
  for (const Mesh& m : s.meshes)
    if (m.name.rfind(prefix, 0) == 0) all.insert(all.end(), m.positions.begin(), m.positions.end());
  return all;
}

bool is_prefix(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  return a.size() <= b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec3)) == 0;
}

// Kinds are placed in this order, each clear of the ones before it.
TEST(OutdoorScene, ADensityRaisesItsKindsCountAndMovesNoKindPlacedBefore) {
  const std::vector<std::pair<std::string, std::string>> kinds = {
      {"buildings", "buildings_"}, {"trees", "leaves"}, {"poles", "poles"}};
  for (size_t k = 0; k < kinds.size(); ++k) {
    const auto& [param, mesh] = kinds[k];
    Scene previous = outdoor({{param, 0.0}});
    for (const double density : {50.0, 150.0, 500.0}) {
      const Scene s = outdoor({{param, density}});
      EXPECT_GT(triangles_of(s, mesh), triangles_of(previous, mesh)) << param << " " << density;
      for (size_t j = 0; j < k; ++j)
        EXPECT_EQ(positions_of(s, kinds[j].second), positions_of(previous, kinds[j].second))
            << param << " " << density << " moved " << kinds[j].first;
      // More buildings or trees: the same ones and more (the street
      // lights are spaced evenly over the road, so they move).
      if (param != "poles") {
        for (const Mesh& m : previous.meshes)
          if (m.name.rfind(mesh, 0) == 0) {
            ASSERT_NE(find_mesh(s, m.name), nullptr) << m.name;
            EXPECT_TRUE(is_prefix(m.positions, find_mesh(s, m.name)->positions))
                << m.name << " " << density;
          }
      }
      previous = s;
    }
  }
}

TEST(OutdoorScene, DefaultsStayUnderTwoHundredThousandTriangles) {
  const Scene s = outdoor();
  EXPECT_LE(s.triangle_count(), 200000u);
  EXPECT_GT(s.triangle_count(), 50000u);
}

TEST(OutdoorScene, AValueOutOfRangeOrOverTheBudgetNamesItsParameter) {
  const SceneType* t = find_scene_type("outdoor");
  ASSERT_NE(t, nullptr) << "no scene type 'outdoor'";
  for (const auto& [param, value] : std::vector<std::pair<std::string, json>>{
           {"extent", 999.0}, {"sun_elevation", 91.0}, {"trees", -1.0}, {"seed", -1}}) {
    try {
      resolve_params(t->params, {{param, value}}, "x.json", "/scenes/0/params");
      ADD_FAILURE() << param << " " << value.dump() << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), "/scenes/0/params/" + param) << e.what();
    }
  }
  const Params big =
      resolve_params(t->params, {{"extent", 20000.0}, {"trees", 5000.0}}, "x.json", "/params");
  const auto [blamed, problem] = t->check(big);
  EXPECT_EQ(blamed, "trees");
  EXPECT_NE(problem.find("over the generators' limit"), std::string::npos) << problem;
  const auto [none, fine] = t->check(resolve_params(t->params, json::object(), "x.json", ""));
  EXPECT_EQ(fine, "");
}

}  // namespace
}  // namespace sb
