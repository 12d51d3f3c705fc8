#include <gtest/gtest.h>

#include <map>

#include "plan/need_resolution.h"
#include "plugin/registry.h"
#include "scenes/need_providers.h"
#include "scenes/sphere_grid.h"
#include "scenes/topology.h"

namespace sb {

using core::AlphaMode;
using core::Mesh;
using core::Scene;
using core::TextureImage;
using plan::Derive;
using plan::resolve_needs;
using plan::ResolvedNeeds;
using plugin::CasterAdjacency;
using plugin::Needs;
using plugin::PlanarReceiver;
using plugin::TechniqueInfo;

namespace {

TEST(Topology, SphereIsClosed) {
  const MeshTopology t = analyse_topology(make_uv_sphere("s", glm::vec3(0), 1.0f, 20, 20));
  EXPECT_TRUE(t.closed());
}

TEST(Topology, QuadHasFourBoundaryEdges) {
  const MeshTopology t = analyse_topology(make_ground_plane("g", glm::vec3(0), 1.0f));
  EXPECT_EQ(t.boundary_edges, 4u);
  EXPECT_EQ(t.nonmanifold_edges, 0u);
  EXPECT_FALSE(t.closed());
}

TEST(Topology, SplitVerticesAreWelded) {
  // A tetrahedron with every triangle on its own three vertices is still closed.
  const glm::vec3 p[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const uint32_t tris[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  Mesh m;
  for (const auto& t : tris)
    for (uint32_t v : t) {
      m.indices.push_back(uint32_t(m.positions.size()));
      m.positions.push_back(p[v]);
    }
  EXPECT_TRUE(analyse_topology(m).closed());
  // Three triangles on one edge: non-manifold.
  m.positions.insert(m.positions.end(), {p[0], p[1], glm::vec3(0, -1, 0)});
  m.indices.insert(m.indices.end(), {12, 13, 14});
  EXPECT_EQ(analyse_topology(m).nonmanifold_edges, 1u);
}

TEST(Topology, FlippedTriangleIsInconsistent) {
  Mesh m = make_uv_sphere("s", glm::vec3(0), 1.0f, 6, 4);
  std::swap(m.indices[0], m.indices[1]);
  const MeshTopology t = analyse_topology(m);
  EXPECT_EQ(t.inconsistent_edges, 3u);
  EXPECT_FALSE(t.closed());
}

TEST(Adjacency, FarVerticesBelongToTheNeighbours) {
  const Mesh m = make_uv_sphere("s", glm::vec3(0), 1.0f, 9, 6);
  const auto adj = build_adjacency_indices(m);
  ASSERT_EQ(adj.size(), m.indices.size() * 2);
  for (size_t t = 0; t < m.triangle_count(); ++t)
    for (size_t e = 0; e < 3; ++e) {
      const uint32_t a = adj[6 * t + 2 * e], far = adj[6 * t + 2 * e + 1];
      const uint32_t b = adj[6 * t + (2 * e + 2) % 6];
      // Find the neighbour (b, a, far) among the triangles, in any rotation.
      bool found = false;
      for (size_t u = 0; u < m.triangle_count() && !found; ++u)
        for (size_t r = 0; r < 3; ++r)
          found = found || (m.indices[3 * u + r] == b && m.indices[3 * u + (r + 1) % 3] == a &&
                            m.indices[3 * u + (r + 2) % 3] == far);
      EXPECT_TRUE(found) << "triangle " << t << " edge " << e;
    }
}

TEST(SceneAnalysis, BuildsOnlyWhatTechniquesNeed) {
  Scene s;
  s.meshes.push_back(make_uv_sphere("s", glm::vec3(0, 2, 0), 1.0f, 8, 6));
  s.meshes.push_back(make_ground_plane("g", glm::vec3(0), 5.0f));
  TechniqueInfo map{"map", "f", "", Needs{}, {}, nullptr};
  TechniqueInfo volume{"volume", "f",
                       "",       Needs{plugin::need::kEdgeAdjacency, plugin::need::kClosedCasters},
                       {},       nullptr};

  const auto before = derived_data_counters();
  ResolvedNeeds r = resolve_needs(s, {&map}, nullptr, Derive::All);
  EXPECT_FALSE(r.data.has(plugin::need::kCasterClosedness));
  EXPECT_FALSE(r.data.has(plugin::need::kEdgeAdjacency));
  EXPECT_EQ(derived_data_counters().adjacency_builds, before.adjacency_builds);
  EXPECT_EQ(derived_data_counters().closedness_checks, before.closedness_checks);

  // Deciding skips checks closedness but builds no adjacency yet.
  r = resolve_needs(s, {&map, &volume}, nullptr, Derive::Decide);
  EXPECT_TRUE(r.data.has(plugin::need::kCasterClosedness));
  EXPECT_FALSE(r.data.has(plugin::need::kEdgeAdjacency));
  EXPECT_EQ(r.skip_reason[1], "");  // the open ground casts nothing
  EXPECT_EQ(derived_data_counters().adjacency_builds, before.adjacency_builds);

  r = resolve_needs(s, {&map, &volume}, nullptr, Derive::All);
  const auto& adjacency = r.data.get<CasterAdjacency>(plugin::need::kEdgeAdjacency);
  EXPECT_EQ(adjacency[0].size(), s.meshes[0].indices.size() * 2);
  EXPECT_TRUE(adjacency[1].empty());

  s.meshes[1].casts_shadow = true;  // now an open caster: skipped, so no adjacency
  const size_t builds = derived_data_counters().adjacency_builds;
  r = resolve_needs(s, {&volume}, nullptr, Derive::All);
  EXPECT_EQ(r.skip_reason[0], "volume needs closed casters: mesh 'g' has 4 boundary edges");
  EXPECT_FALSE(r.data.has(plugin::need::kEdgeAdjacency));
  EXPECT_EQ(derived_data_counters().adjacency_builds, builds);
}

}  // namespace
}  // namespace sb

namespace sb {
namespace {

TEST(PlanarReceiver, FoundUnderTheCastersOnly) {
  Scene s;
  s.meshes.push_back(make_uv_sphere("s", glm::vec3(0, 2, 0), 1.0f, 8, 6));
  s.meshes.push_back(make_ground_plane("g", glm::vec3(0), 5.0f));
  s.light.center = glm::vec3(0, 10, 0);
  PlanarReceiver r;
  ASSERT_TRUE(find_planar_receiver(s, r));
  EXPECT_EQ(r.mesh, "g");
  EXPECT_NEAR(r.plane.y, 1.0f, 1e-6f);  // facing the casters and the light
  EXPECT_NEAR(r.plane.w, 0.0f, 1e-6f);

  // A plane cutting through the sphere receives nothing of it.
  s.meshes[1] = make_ground_plane("g", glm::vec3(0, 2, 0), 5.0f);
  EXPECT_FALSE(find_planar_receiver(s, r));

  // Only asked for when a technique needs it.
  TechniqueInfo planar{"planar", "f", "", Needs{plugin::need::kPlanarReceiver}, {}, nullptr};
  TechniqueInfo map{"map", "f", "", Needs{}, {}, nullptr};
  const size_t before = derived_data_counters().receiver_searches;
  EXPECT_EQ(resolve_needs(s, {&map}, nullptr, Derive::Decide).skip_reason[0], "");
  EXPECT_EQ(derived_data_counters().receiver_searches, before);
  EXPECT_EQ(resolve_needs(s, {&planar}, nullptr, Derive::Decide).skip_reason[0],
            "planar needs a planar receiver under every caster; the scene has none");
  EXPECT_EQ(derived_data_counters().receiver_searches, before + 1);
}

TEST(Capabilities, AlphaTestedCastersSkipTechniquesThatCannotHonourThem) {
  Scene s;
  s.textures.push_back(TextureImage{"t", 1, 1, {255, 255, 255, 0}});
  Mesh closed = make_uv_sphere("masked", glm::vec3(0, 2, 0), 1.0f, 8, 6);
  closed.uvs.assign(closed.positions.size(), glm::vec2(0.5f));
  closed.base_color_texture = 0;
  closed.alpha_mode = AlphaMode::Mask;
  s.meshes.push_back(closed);
  TechniqueInfo volume{"volume", "f",
                       "",       Needs{plugin::need::kClosedCasters, plugin::need::kOpaqueCasters},
                       {},       nullptr};
  EXPECT_EQ(resolve_needs(s, {&volume}, nullptr, Derive::Decide).skip_reason[0],
            "volume cannot honour alpha masks: mesh 'masked' is alpha-tested");
}

}  // namespace
}  // namespace sb
