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

// A perspective view from a light point (fit_light_frustum() makes one), or
// under the sun an orthographic one along its direction (fit_sun_frustum()):
// its matrices, eye, near and far planes and half field of view.
// units: world units; tan_half_fov is a tangent (map half-extent per unit
// distance along the axis), perspective only; half_extent (world units) is
// the orthographic map's half side.
struct LightFrustum {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
  glm::mat4 view_projection{1.0f};
  glm::vec3 eye{0.0f};
  float near_plane = 0.1f;
  float far_plane = 100.0f;
  float tan_half_fov = 1.0f;
  // An orthographic map (the sun's): window depth is linear in view depth,
  // every texel has the same world size, and `eye` is only the view's
  // origin (a place on the sun's side of every point of the scene).
  bool orthographic = false;
  float half_extent = 0.0f;  // orthographic only: half the map's side, world units
  // World-space size of one texel of a size×size map, per unit distance from
  // eye (perspective only).
  float texel_per_distance(int size) const { return 2.0f * tan_half_fov / float(size); }
  // World-space size of one texel of a size×size orthographic map.
  float texel_world(int size) const { return 2.0f * half_extent / float(size); }
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

// The sun's frame: a rotation only (its origin is the world's), looking
// along `direction` (the way light travels), +y as close to the world's +y
// as the direction allows. Fixed while the light is, whatever the camera
// does (cascaded shadow maps snap their texels in it).
// units: none (a rotation).
// cost: O(1); no GL.
glm::mat4 light_rotation(const glm::vec3& direction);

// The sun's single map (`scene.light.is_sun()`): an orthographic view along
// scene.light.direction(), the light frame of cascaded shadow maps (square,
// +y as close to the world's +y as the direction allows).
//   x/y    the casters' extent seen along the light (every vertex a caster
//          triangle references), as fit_light_frustum() fits it, grown by
//          how far the sun's disk moves a shadow over the depth range
//          ((far − caster) · tan(α/2) for angular diameter α): receivers
//          outside it cannot be shadowed, so they are lit by construction
//          (the map's border reads "far"). Fitting the casters and not the
//          whole scene keeps the texels on what casts: a ground that
//          reaches past every caster would otherwise take them;
//   depth  the depth range along the light of the scene's bounding box
//          (every caster and every receiver), with a 1% margin each side:
//          near_plane > 0 at the eye, a point on the sun's side of the box;
//   out    half_extent, orthographic = true, tan_half_fov unused; with no
//          caster view_projection is the identity and every point is lit.
// units: world units.
// cost: one matrix-vector product per caster index; no GL, no allocation.
LightFrustum fit_sun_frustum(const core::Scene& scene);

// The map a single-map technique draws from the scene's light: the sun's
// orthographic fit under the sun, else the perspective fit from the light's
// centre (fit_light_frustum(scene, scene.light.center)).
// units: world units.
// cost: as the fit it calls.
LightFrustum fit_single_map_frustum(const core::Scene& scene);

}  // namespace sb::techniques
