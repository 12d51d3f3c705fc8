#pragma once
// The data the harness's needs give a technique (plugin/needs.h), read with
// FrameInputs::derived->get<T>(name).
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "plugin/silhouette_edges.h"

namespace sb {

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

}  // namespace sb
