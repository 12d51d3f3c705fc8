#pragma once
// The objects of the outdoor scene (scenes/outdoor.cpp), each standing on
// the ground y = 0 at (x, z) and appended to the mesh of its kind: closed
// meshes for buildings, wood and poles, alpha-tested quads for leaves.
// Sizes are in metres; the triangle counts are what check_outdoor budgets.
#include <cstdint>

#include "core/scene.h"
#include "scenes/draws.h"

namespace sb {

// A box of footprint 2·half_x × 2·half_z and `height`, turned by `yaw`
// radians about y; with a `tier_height` above 0, a box of 0.6 of the
// footprint and that height on top (sunk 0.1 into the lower one, so that
// the two closed boxes share no face). 12 or 24 triangles.
void add_building(core::Mesh& into, glm::vec2 at, float half_x, float half_z, float height,
                  float yaw, float tier_height);
inline constexpr uint64_t kBuildingTriangles = 24;  // at most

// A tree: a trunk of `trunk_height` and `trunk_radius`, three limbs into a
// crown (an ellipsoid of horizontal radius `crown_radius`, 1.2× that
// vertically, centred 0.8 of its vertical radius above the trunk's top) and
// `leaves` alpha-tested quads of side `leaf_size` in its outer shell, every
// corner at least 0.05 above the ground.
struct TreeShape {
  float trunk_height = 3.0f;
  float trunk_radius = 0.2f;
  float crown_radius = 2.5f;
  int leaves = 100;
  float leaf_size = 0.5f;
};
void add_tree(core::Mesh& wood, core::Mesh& leaves, glm::vec2 at, const TreeShape& shape,
              Draws& draws);
// Triangles of the wood of one tree (the leaves add 2 each).
inline constexpr uint64_t kTreeWoodTriangles = 4 * 6 + 3 * 4 * 5;

// A street light: an 8 m tapered pole (0.10 to 0.07 radius), an arm of
// 1.6 m towards `facing` (a horizontal direction) and a lamp head at its end.
void add_street_light(core::Mesh& into, glm::vec2 at, glm::vec2 facing);
// A wooden power pole, 0.16 to 0.12 radius, `height`, with a 2.4 m cross-arm
// 0.6 below its top, across `yaw`.
void add_power_pole(core::Mesh& into, glm::vec2 at, float height, float yaw);
// A sign post of radius 0.035 and `height`, carrying a 0.6 × 0.6 × 0.03
// plate at its top facing `yaw`.
void add_sign_post(core::Mesh& into, glm::vec2 at, float height, float yaw);
// A bollard: 0.1 radius, 0.9 high.
void add_bollard(core::Mesh& into, glm::vec2 at);
inline constexpr uint64_t kPoleTriangles = 4 * 8 + 12 + 12;  // at most, of any of the four

}  // namespace sb
