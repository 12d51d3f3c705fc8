#pragma once
// Penumbra wedges on the CPU (Akenine-Möller & Assarsson 2002; Assarsson &
// Akenine-Möller 2003): for a silhouette edge a → b and a rectangular area
// light L, the wedge is the set of points whose view of L the edge can cut,
//   S = { y : the segment from some light point l to y meets the edge }.
//
// In the light's frame (common/light_frame.h: the light in z = 0, the scene at
// z > 0), S cut at a plane z = Z beyond the edge is the convex hull of two
// rectangles: L seen through each end point and projected onto z = Z
// (point-reflected and scaled by Z/z − 1 about the end point's own
// projection). So S ∩ {z <= Z} is exactly the convex hull of the two end
// points and those two rectangles' eight corners. We build that hull with Z
// beyond every scene point; its faces are wound outwards, so a pixel whose
// surface point may lie in the wedge is drawn exactly once by the hull's back
// faces (the exit of the view ray), with the depth test rejecting surfaces
// behind the exit.
//
// Beside the hull, each wedge carries the planes of Lengyel's half-wedge
// test (GDC 2005): the plane through the edge and the light's centre splits
// the wedge in two, and a point in one half is inside the wedge iff it is on
// the inner side of that half's bounding plane, the plane through the edge
// and the light corner that bounds it.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "common/light_frame.h"
#include "core/scene.h"
#include "shadow_volume/silhouette.h"

namespace sb::techniques::penumbra_wedge {

// One wedge as the fragment shader reads it (std430: five vec4).
struct WedgeRecord {
  glm::vec4 a{0.0f};  // the edge's start, light frame; w: its silhouette's number (a tag)
  glm::vec4 b{0.0f};  // the edge's end, light frame (w unused)
  // World-space planes (n, d), |n| = 1: n·x + d. The centre plane splits the
  // wedge; where it is negative the point must have first_bound >= −τ,
  // elsewhere second_bound >= −τ, with τ = kHalfWedgeTolerance × the point's
  // distance from the light's centre (points on the edge itself round either
  // way). All zero: no rejection (the edge's line meets the
  // light, and the wedge is not bounded by two planes).
  glm::vec4 centre_plane{0.0f};
  glm::vec4 first_bound{0.0f};
  glm::vec4 second_bound{0.0f};
};

constexpr float kHalfWedgeTolerance = 1e-5f;

struct WedgeVertex {
  glm::vec3 position;  // world
  uint32_t wedge;      // index of its WedgeRecord
};

// append_wedge's working storage, kept so that a frame allocates little.
struct WedgeScratch {
  std::vector<std::vector<glm::vec3>> faces, kept;
  std::vector<glm::vec3> rim;
};

struct WedgeBatch {
  std::vector<WedgeVertex> vertices;
  std::vector<uint32_t> indices;  // triangles, wound outwards
  std::vector<WedgeRecord> wedges;
  WedgeScratch scratch;
  void clear() {
    vertices.clear();
    indices.clear();
    wedges.clear();
  }
};

// Where the wedges are cut: edge parts closer to the light's plane than
// `near` (light-frame z) are dropped, since through them the light would be
// projected to near infinity; parts beyond `far` (no scene point lies there)
// too. The hull's far cap lies beyond `far`, and the hull is cut to `box`
// (world; none when empty), where every surface point lies.
struct WedgeRange {
  float near = 1e-3f;
  float far = 1.0f;
  core::Bounds box;
};
// The range for a scene within `scene` (world): `far` at its farthest corner
// from the light's plane, the box a little larger than `scene`.
WedgeRange wedge_range(const LightFrame& frame, const core::Bounds& scene);

// Appends the wedge of the edge a → b (world). Returns false, appending
// nothing, when no part of the edge lies within `range` or it has no length.
bool append_wedge(const LightFrame& frame, const glm::vec3& a, const glm::vec3& b,
                  const WedgeRange& range, WedgeBatch& out);

// A silhouette's wedges: one per edge of every loop (its smooth positions,
// the curve the volume's sides start from), as a range of `out.indices`.
struct IndexRange {
  uint32_t first = 0;
  uint32_t count = 0;
};
// Each record's a.w holds `tag`.
IndexRange append_silhouette_wedges(const LightFrame& frame,
                                    const shadow_volume::Silhouette& silhouette,
                                    const WedgeRange& range, float tag, WedgeBatch& out);

}  // namespace sb::techniques::penumbra_wedge
