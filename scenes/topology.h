#pragma once
// Derived mesh data that only some techniques need: edge adjacency and
// closedness. Built on demand (see scenes/need_providers.h), never eagerly.
#include <cstdint>
#include <vector>

#include "core/scene.h"
#include "plugin/need_data.h"

namespace sb {

struct MeshTopology {
  size_t boundary_edges = 0;      // edges used by one triangle
  size_t nonmanifold_edges = 0;   // edges used by three or more triangles
  size_t inconsistent_edges = 0;  // edges whose two triangles wind the same way
  bool closed() const {
    return boundary_edges == 0 && nonmanifold_edges == 0 && inconsistent_edges == 0;
  }
};

// Counts boundary, non-manifold and inconsistently wound edges. Vertices are
// welded by exact position first, so split normals or UV seams do not open a
// mesh.
MeshTopology analyse_topology(const core::Mesh& mesh);

// Index buffer for GL_TRIANGLES_ADJACENCY: per triangle (v0,a01,v1,a12,v2,a20)
// where aij is the far vertex of the neighbour across edge vi-vj. A boundary
// edge repeats the triangle's own opposite vertex.
std::vector<uint32_t> build_adjacency_indices(const core::Mesh& mesh);

// Every edge of a mesh once (MeshEdge, plugin/need_data.h).
std::vector<plugin::MeshEdge> mesh_edges(const core::Mesh& mesh);

}  // namespace sb
