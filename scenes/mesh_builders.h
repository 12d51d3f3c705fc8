#pragma once
// Closed primitives for procedural scenes. Every builder returns a mesh that
// analyse_topology() calls closed, wound counter-clockwise seen from outside,
// with per-vertex normals: smooth on curved surfaces, flat (vertices
// duplicated) across sharp edges. Duplicates share bit-identical positions, so
// welding by position closes them. Builders throw std::invalid_argument on
// degenerate input (non-positive sizes, too few segments, a zero axis).
#include <string>

#include "core/scene.h"

namespace sb {

// An axis-aligned box rotated by `rotation` (orthonormal) about its centre:
// 12 triangles, 24 vertices.
core::Mesh make_box(const std::string& name, glm::vec3 center, glm::vec3 half_extents,
                    const glm::mat3& rotation = glm::mat3(1.0f));

// A capped (truncated) cone from `base_center` along `axis` (normalised here)
// for `height`, with `segments` sides. A zero radius closes that end in an
// apex instead of a cap. Triangles: 4*segments, minus 2*segments per apex.
core::Mesh make_cylinder(const std::string& name, glm::vec3 base_center, glm::vec3 axis,
                         float radius_bottom, float radius_top, float height, int segments);

// A ring torus around `axis` (normalised here): 2*segments_major*segments_minor
// triangles. Requires 0 < minor < major so the tube does not self-intersect.
core::Mesh make_torus(const std::string& name, glm::vec3 center, glm::vec3 axis, float major,
                      float minor, int segments_major, int segments_minor);

// Applies `transform` to positions, and its inverse transpose to normals. A
// mirroring transform (negative determinant) also reverses every triangle so
// the mesh stays counter-clockwise outward. An analytic sphere moves with the
// mesh; a transform that is not a similarity throws std::invalid_argument.
void transform_mesh(core::Mesh& mesh, const glm::mat4& transform);

// Appends `src`'s geometry to `dst` (dst keeps its name and material). The
// result is closed when both are closed and share no vertex position. Meshes
// with an analytic shape are not merged (std::invalid_argument).
void append_mesh(core::Mesh& dst, const core::Mesh& src);

}  // namespace sb
