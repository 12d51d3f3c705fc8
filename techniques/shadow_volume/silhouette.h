#pragma once
// Silhouette loops of a closed caster seen from a point light, on the CPU, in
// the three modes of Mattausch, Scherzer, Wimmer and Igarashi 2012:
//
//   discrete  the edges between triangles that face the light and triangles
//             that do not (the geometric normal): today's geometry shader.
//   accurate  the silhouette of the smooth surface that the vertex normals
//             define: f = n·(l − v) is interpolated linearly across each
//             triangle from its corners, and the loop runs where f = 0, through
//             the points (1−u)·f_i + u·f_j = 0 on the edges.
//   smooth    the accurate loop lifted onto the curved PN triangle of each
//             triangle (pn_triangle.h: cubic Hermite edges with tangents from
//             the normals), subdivided until |(p0+p1)/2 − p(mid)| < ε, and
//             moved `offset` along the negative normal.
//
// In every mode the lit region R of the mesh (the parts with f > 0) is the
// shadow volume's near cap, and the loops are R's boundary, oriented as the
// mesh winds R. On an edge whose two triangles disagree (a crease, with a
// normal per side; or a discrete silhouette edge), the part lit on one side
// only is itself a boundary piece, so a crease crossing gets two silhouette
// vertices joined along the edge. In smooth mode each loop vertex has two
// positions: `mesh`, on R's boundary, and `smooth`, on the curved surface;
// the volume closes the gap between them with a strip (volume_mesh.h).
//
// A corner counts as lit when f > 0, and an edge is crossed only between a
// lit and an unlit corner, so u = f_i / (f_i − f_j) never divides by less
// than |f_i| > 0: f ≈ 0 at both ends gives a point on the edge, never a NaN.
// Each edge's crossing is computed once, in the edge's own direction, so both
// triangles of a smooth edge find the bit-identical point.
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/scene.h"
#include "plugin/need_data.h"

namespace sb::techniques::shadow_volume {

enum class SilhouetteMode { Discrete, Accurate, Smooth };
// "discrete", "accurate" or "smooth"; throws std::invalid_argument otherwise.
SilhouetteMode silhouette_mode_from_string(const std::string& s);

struct SilhouetteSettings {
  SilhouetteMode mode = SilhouetteMode::Discrete;
  float epsilon = 0.01f;  // smooth: subdivision tolerance, world units
  float offset = 0.0f;    // smooth: displacement along the negative normal, world units
  int max_depth = 8;      // smooth: at most 2^max_depth pieces per triangle
};

// A caster's triangles and edges, prepared once from the scene (no light).
struct SilhouetteMesh {
  static constexpr uint32_t kNone = 0xffffffffu;
  std::vector<glm::vec3> positions;     // per corner, 3 per triangle
  std::vector<glm::vec3> normals;       // per corner, unit (the face's when absent)
  std::vector<glm::vec3> face_normals;  // per triangle, unit
  std::vector<uint32_t> welded;         // per corner: its position's id (exact welding)
  struct Edge {
    uint32_t left_corner = kNone;   // corner of `left` where the edge starts (v0)
    uint32_t right_corner = kNone;  // corner of `right` where it starts (v1), or kNone
  };
  std::vector<Edge> edges;
  std::vector<uint32_t> edge_of_corner;  // the edge from corner c to the next corner
};
SilhouetteMesh make_silhouette_mesh(const core::Mesh& mesh,
                                    const std::vector<plugin::MeshEdge>& edges);

struct SilhouetteVertex {
  glm::vec3 mesh;    // on the lit region's boundary, on the mesh
  glm::vec3 smooth;  // where the volume's side starts (== mesh unless smooth)
};

namespace detail {
// One piece of the lit region's boundary, from `a` to `b` (silhouette.cpp).
struct Segment {
  uint64_t from = 0, to = 0;  // keys of the end points: a mesh vertex, or an edge and its u
  SilhouetteVertex a, b;
  uint32_t inner_first = 0, inner_count = 0;  // subdivision points
};
}  // namespace detail

// Working storage of extract_silhouette, kept so that a frame allocates
// nothing once the first has run.
struct SilhouetteScratch {
  std::vector<float> f;  // per corner
  std::vector<detail::Segment> segments;
  std::vector<SilhouetteVertex> inner;
  std::vector<glm::vec3> fan;
  std::vector<std::pair<uint64_t, uint32_t>> order;
  std::vector<char> used;
};

struct Silhouette {
  // Closed loops: the last vertex connects to the first.
  std::vector<std::vector<SilhouetteVertex>> loops;
  size_t open_loops = 0;  // loops that could not be closed (0 on a closed mesh)
  // The lit region as triangles (3 vertices each, wound as the mesh), its
  // edges meeting the loops' `mesh` positions vertex to vertex.
  std::vector<glm::vec3> cap;
  SilhouetteScratch scratch;
};

// Fills `out` (reusing its storage) for the light at `light`.
void extract_silhouette(const SilhouetteMesh& mesh, const glm::vec3& light,
                        const SilhouetteSettings& settings, Silhouette& out);

}  // namespace sb::techniques::shadow_volume
