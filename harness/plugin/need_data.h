#pragma once
// The data the harness's needs give a technique (plugin/needs.h), read with
// FrameInputs::derived->get<T>(name).
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "plugin/silhouette_edges.h"

namespace sb::plugin {

// need::kPlanarReceiver: a planar mesh with every caster on the light's side
// of its plane.
struct PlanarReceiver {
  std::string mesh;
  glm::vec4 plane{0.0f};  // (n, d): n·x + d = 0, n towards the casters
};

// need::kEdgeAdjacency: per scene mesh, GL_TRIANGLES_ADJACENCY indices of a
// caster (6 per triangle), empty for receivers. Drawn by
// GpuScene::draw_casters_adjacency.
using CasterAdjacency = std::vector<std::vector<uint32_t>>;

// One edge of a mesh, vertices welded by exact position (split normals or UV
// seams do not open a mesh). An edge with exactly two oppositely wound
// triangles names both; any other edge (boundary, non-manifold,
// inconsistently wound) appears once per triangle using it, with only that
// triangle, so no face is ever paired with the wrong neighbour.
struct MeshEdge {
  uint32_t v0 = 0, v1 = 0;  // mesh vertex indices, as triangle `left` winds them
  uint32_t left = 0;        // the triangle that winds v0 → v1
  int64_t right = -1;       // the triangle that winds v1 → v0, or -1
};

// need::kCasterEdges: per scene mesh, every edge of a caster once (empty for
// receivers), for techniques that find silhouettes on the CPU.
using CasterEdges = std::vector<std::vector<MeshEdge>>;

}  // namespace sb::plugin
