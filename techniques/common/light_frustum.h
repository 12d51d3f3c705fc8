#pragma once
// A perspective light view from one point of the area light, looking along
// the light's axis, fitted off-axis to the casters' projected extent (every
// vertex a caster triangle references) with the near plane at the nearest
// caster: receivers outside it cannot be shadowed from that point, so they
// are lit by construction (the map's border reads "far"). The map is square
// with square texels; tan_half_fov is its half-extent in x/z (and y/z).
//
// What the kit guarantees here (shadowbench::shadow_kit, installed):
//   in     the scene on the CPU (its casters' triangles, its light, its
//          bounds) and the eye, a point in world units, normally
//          scene.light.center (or any point of the light);
//   out    view (glm::lookAt from the eye along the light's axis), an
//          off-axis GL projection (clip z in [-w, w]) and their product;
//          near_plane = 0.99 × the nearest caster's distance along the axis,
//          far_plane = 1.01 × the farthest point of the scene's bounding box
//          inside the frustum (so every receiver the map covers has a depth
//          in [0, 1]); all in world units. With no caster at all, view_projection is the
//          identity and every point is lit;
//   GL     none: plain CPU code, safe without a context;
//   cost   one matrix-vector product per caster index (every index of every
//          caster mesh), no allocation. Call it in render(), every frame,
//          inside the timed pass that uses it: it depends on the light.
#include <glm/glm.hpp>

#include "core/scene.h"

namespace sb::techniques {

// A perspective view from a light point (fit_light_frustum() makes one):
// its matrices, eye, near and far planes and half field of view.
// units: world units; tan_half_fov is a tangent (map half-extent per unit
// distance along the axis).
struct LightFrustum {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
  glm::mat4 view_projection{1.0f};
  glm::vec3 eye{0.0f};
  float near_plane = 0.1f;
  float far_plane = 100.0f;
  float tan_half_fov = 1.0f;
  // World-space size of one texel of a size×size map, per unit distance from eye.
  float texel_per_distance(int size) const { return 2.0f * tan_half_fov / float(size); }
};

// The frustum of a map from `eye` (the rule at the top of this header).
// Throws sb::JobError, naming the mesh, when a caster reaches the plane of the
// light through `eye` or behind it, or when the casters span nearly 180°
// from `eye`: a single perspective map cannot cover them.
// `widen_for_light`: grow the extent by how far the light's rectangle moves
// each caster's shadow (for maps whose filters reach into the outer
// penumbra); false fits the casters alone, for hard maps from points that
// are not on the light (two_map_bound's apexes).
// units: world units.
// cost: one matrix-vector product per caster index; no GL, no allocation.
LightFrustum fit_light_frustum(const core::Scene& scene, const glm::vec3& eye,
                               bool widen_for_light = true);

}  // namespace sb::techniques
