#pragma once
// How occlusion textures cut the space between the light and the scene
// (Eisemann & Décoret 2008, §3–4), on the CPU: the technique's shaders
// repeat these formulas, and tests/techniques/test_occlusion_slicing.cpp
// checks them against rays traced by hand.
//
// In the light's frame (common/light_frame.h: the light is the rectangle
// |x| <= hw, |y| <= hh of z = 0, the scene at z > 0) the casters' depth
// range is cut into `slabs` slabs of equal thickness t; slab k spans
// [z0 + k·t, z0 + (k + 1)·t]. Each slab's casters are projected into one
// binary texture, texture coordinates
//   q(x, y, z) = (xy − origin) ∘ scale / (a·z + b) + ½,
// with one of two projections:
//   central       from a centre C behind the light, at the distance D that
//                 fits the frustum to the light: the frustum's cross-section
//                 at z = 0 is the light rectangle, and it widens just enough
//                 to hold every caster (a = 1, b = D, origin 0, scale =
//                 D / (2hw, 2hh)). Its lines all pass through the light, so
//                 a slab's content is projected along directions close to
//                 those of the shadow rays that cross it. With every caster
//                 inside the light's own footprint D is infinite: the
//                 projection is the parallel one over that footprint. A light
//                 of no area puts C at its centre (D = 0).
//   orthographic  along the light's normal over the casters' square extent
//                 (a = 0, b = 1): a slab's content is projected straight down,
//                 which shadow rays from receivers off the light's axis cross
//                 at a slant, and through which they leak.
//
// The part of slab k that counts for a point p is [z_k, min(z_{k+1},
// p.z − β·t)]: all of the slab once p lies β slabs beyond it, part of it
// while p is closer, none when the slab lies behind p − β·t. Its weight is
// its length over t (the linear fade). p sees the light through one plane
// of that part (LookupPlane): its far side, the slice's far plane once the
// whole slab counts (the paper's), or its middle. The kernel is the light
// rectangle projected from p onto that plane, centre p.xy·z/p.z, half sizes
// (hw, hh)·(1 − z/p.z); its occlusion is that rectangle's box-filtered
// mean of the texture. β, the self-shadow offset, keeps a point from
// reading its own surface in its own slab (β = 1: the slab that holds p
// never counts, the one in front of it fades in while p crosses its own).
// SelfSlab says who takes it: every point (the paper's rule, which needs
// no caster/receiver split), or casters only, a receiver that casts
// nothing (in no texture) reading its own slab up to its depth.
#include <glm/glm.hpp>

#include "common/light_frame.h"
#include "core/scene.h"

namespace sb::techniques::occlusion_texture {

enum class Projection { Central, Orthographic };
Projection projection_from_string(const std::string& s);  // "central" | "orthographic"

enum class LookupPlane { Far, Mid };
LookupPlane lookup_plane_from_string(const std::string& s);  // "far" | "mid"
// Where the plane lies in the part that counts: 1 its far side, ½ its middle.
float plane_fraction(LookupPlane plane);

enum class SelfSlab { Skip, ReceiverAware };
SelfSlab self_slab_from_string(const std::string& s);  // "skip" | "receiver_aware"
// The offset β a point takes: `caster_offset` for a caster's point, and for
// a receiver's the same (Skip) or none (ReceiverAware).
float point_offset(SelfSlab rule, bool casts_shadow, float caster_offset);

struct TextureBox {
  glm::vec2 lo{0.0f}, hi{0.0f};  // texture coordinates, [0, 1] over the texture
};

struct SlabShare {
  float weight = 0.0f;  // in [0, 1]
  float plane = 0.0f;   // light-frame depth of the plane p looks through
};

struct Slicing {
  LightFrame light;
  int slabs = 0;
  float z0 = 0.0f;         // the first slab's near side
  float thickness = 1.0f;  // t
  bool no_casters = false;
  // q = (xy − origin) ∘ scale / (a·z + b) + ½
  glm::vec2 origin{0.0f};
  glm::vec2 scale{1.0f};
  float a = 0.0f, b = 1.0f;

  float mid_plane(int k) const { return z0 + (float(k) + 0.5f) * thickness; }
  float far_plane(int k) const { return z0 + float(k + 1) * thickness; }
  // `local`: a point in the light's frame.
  glm::vec2 texture_coords(const glm::vec3& local) const;
  // How much of slab k counts for a point at depth z, with offset β (slabs),
  // and the plane it is read through.
  SlabShare share(float z, int k, float offset, LookupPlane plane) const;
  // Where p (light frame) sees the light through the plane at depth `plane`.
  TextureBox kernel(const glm::vec3& p, float plane) const;
};

// Throws JobError, naming the mesh, when a caster reaches the light's plane.
Slicing fit_slicing(const core::Scene& scene, int slabs, Projection projection);

}  // namespace sb::techniques::occlusion_texture
