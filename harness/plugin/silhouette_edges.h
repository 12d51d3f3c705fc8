#pragma once
// The data of need::kSilhouetteEdges: every edge of the casters once, with
// the planes of the faces on either side, in one shader storage buffer.
//
// std430 layout, 64 bytes per edge, in world space:
//   struct Edge {
//     vec4 p0;       // xyz: first endpoint; w: mesh index
//     vec4 p1;       // xyz: second endpoint; w: 1 with two faces, 0 without
//     vec4 plane_a;  // the face that winds p0 → p1: n·x + d = 0, n outwards
//     vec4 plane_b;  // the face across the edge (winds p1 → p0); 0 if none
//   };
// An edge with two faces is on the silhouette from a point L when
// dot(plane_a, L) and dot(plane_b, L) (with L.w = 1) differ in sign. An edge
// with one face (a boundary, or one of three or more faces meeting at a
// non-manifold edge) is a silhouette whenever its face is lit from either
// side; shaders test it by that face alone.
#include <cstdint>
#include <vector>

#include "gl/objects.h"

namespace sb::plugin {

struct SilhouetteEdges {
  static constexpr GLsizeiptr kBytesPerEdge = 64;
  gl::Buffer storage;  // GL_SHADER_STORAGE_BUFFER, read-only for techniques
  GLuint buffer() const { return storage.get(); }
  GLsizei edge_count = 0;
  struct MeshRange {
    GLint first_edge = 0;
    GLsizei edge_count = 0;
  };
  std::vector<MeshRange> meshes;  // per scene mesh; empty ranges for receivers
};

}  // namespace sb::plugin
