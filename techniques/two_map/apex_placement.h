#pragma once
// Where Shypula 2008 (ch. 8, figures 8.4–8.5) puts the two shadow maps of
// the two-map penumbra bound, from the light's rectangle and the casters'
// extent, in the light's frame (common/light_frame.h: the light is the
// rectangle |x| <= l_x, |y| <= l_y of z = 0, the scene at z > 0).
//
// Per axis, with the casters' extent [lo, hi] at their nearest depth D
// (c = (hi − lo)/2 its half-width):
//   penumbra apex: where the lines from each edge of the light to the
//     casters' opposite edge cross, in front of the light,
//       z_p = D · l / (c + l);
//     hidden from it is every point behind the extent that some light point
//     cannot see: the whole penumbra of one occluder as wide as the extent.
//   umbra apex: where the lines from each edge of the light to the casters'
//     same edge cross, behind the light when the casters are wider (c > l),
//       z_u = −D · l / (c − l);
//     hidden from it is the umbra of that occluder. When c = l the lines are
//     parallel (the apex at infinity) and when c < l they cross beyond the
//     casters: no point behind them is hidden from the whole light by the
//     extent, and the technique runs without an umbra map.
// Both apexes lie on the line from the extent's centre through the light's
// centre. Along that line, an apex farther from the light casts the larger
// shadow of the extent's edges (at the crossing it casts exactly the
// boundary). So in 3D the penumbra apex takes the axis whose crossing is
// farther from the light, and the umbra apex the axis whose crossing is
// farther behind it: each then bounds its class on both axes. An umbra
// apex farther than kFarthestUmbraApex · D behind the light is placed there:
// its map is then nearly orthographic, and a perspective map from farther
// away would have too little depth precision left (its near and far planes
// within a few percent of each other).
#include <glm/glm.hpp>

#include "common/light_frame.h"
#include "core/scene.h"

namespace sb::techniques::two_map {

inline constexpr float kFarthestUmbraApex = 100.0f;

struct TwoApexes {
  float caster_depth = 0.0f;      // D, along the light's axis
  glm::vec3 penumbra_apex{0.0f};  // world
  float penumbra_depth = 0.0f;    // z_p, light frame
  bool has_umbra_apex = false;    // false when the light is as wide as the casters
  glm::vec3 umbra_apex{0.0f};     // world, when has_umbra_apex
  float umbra_depth = 0.0f;       // z_u (< 0 behind the light)
};

// `casters`: the casters' bounding box (world). Throws sb::JobError when
// it reaches the light's plane (D <= 0).
TwoApexes place_apexes(const LightFrame& light, const core::Bounds& casters);

}  // namespace sb::techniques::two_map
