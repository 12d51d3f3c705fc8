#pragma once
// The CPU side of cascaded shadow maps: where the camera's depth range is
// split (the practical split scheme of parallel-split shadow maps, Zhang et
// al. 2006), the camera-frustum slice each cascade covers, and the
// orthographic light box fitted to it, stable (Valient 2008: the slice's
// bounding sphere, its centre snapped to whole texels in light space) or
// tight (the slice's light-space bounding box, which shimmers).
//
// Plain CPU code: no GL, no allocation beyond the returned vectors; called in
// render(), every frame, inside the timed pass (it depends on the light and
// the camera). units: world units throughout; depths along the camera's
// axis are view depths (positive in front of the eye).
#include <array>
#include <glm/glm.hpp>
#include <vector>

#include "common/light_frustum.h"

namespace sb::techniques::cascaded {

// The practical split scheme: split i of N over [n, f] is
//   C_i = λ·n·(f/n)^(i/N) + (1 − λ)·(n + (f − n)·i/N),
// the blend of the logarithmic scheme (λ = 1, constant texel-to-pixel ratio
// along the view) and the uniform one (λ = 0). Returns N + 1 depths,
// C_0 = n to C_N = f. Needs 0 < n < f, N >= 1, λ in [0, 1].
std::vector<float> practical_splits(float near_plane, float far_plane, int cascades, float lambda);

// A symmetric perspective camera: its world-to-view matrix (glm::lookAt's),
// the tangent of its half vertical field of view and its aspect (w / h).
struct CameraFrustum {
  glm::mat4 view{1.0f};
  float tan_half_fov_y = 0.4142f;
  float aspect = 1.0f;
};

// The 8 world-space corners of the camera frustum between view depths d0
// and d1: the near rectangle's four (x−y−, x+y−, x+y+, x−y+), then the far one's.
std::array<glm::vec3, 8> slice_corners(const CameraFrustum& camera, float d0, float d1);

struct Sphere {
  glm::vec3 center{0.0f};
  float radius = 0.0f;
};

// The smallest sphere holding the slice between d0 and d1 (centred on the
// camera's axis). Its radius depends on d0, d1, the field of view and the
// aspect only, never on where the camera is or how it is turned: a stable
// cascade's extent is constant.
Sphere slice_bounding_sphere(const CameraFrustum& camera, float d0, float d1);

// The light's frame (common/light_frustum.h, shared with the single map's
// sun fit): texel snapping is done in it.
using techniques::light_rotation;

// One cascade's orthographic light box, in the light's frame (light_rotation):
// x in [lo.x, hi.x], y in [lo.y, hi.y], and the depth range along the light
// (distances in front of the frame's origin, along `direction`) from
// near_depth to far_depth.
struct CascadeBox {
  glm::vec2 lo{0.0f};
  glm::vec2 hi{0.0f};
  float near_depth = 0.0f;
  float far_depth = 1.0f;
  // World units per texel along x (the box is square: also along y).
  float texel = 0.0f;
  glm::mat4 view{1.0f};             // light_rotation(direction)
  glm::mat4 projection{1.0f};       // glm::ortho of the box
  glm::mat4 view_projection{1.0f};  // projection * view
};

// How a cascade's box is fitted to its slice.
enum class FitMode {
  // Valient 2008: the slice's bounding sphere; the box is its circumscribed
  // square (side 2r, constant), its centre snapped to whole texels of a
  // size×size map in the light's frame. A world point then moves in the map
  // by whole texels only as the camera moves: no shimmering.
  Stable,
  // The light-space bounding box of the slice's 8 corners: fewer wasted
  // texels, but its extent and origin change with every camera motion.
  Tight,
};

// The box of the slice between view depths d0 and d1, for a size×size map.
// Its depth range runs from the nearest of `caster_corners` along the light
// (so casters outside the slice that shadow it are in the map) to the
// farthest point of the slice's fit (sphere or corners), both with a small
// margin. `caster_corners`: the casters' bounding box corners (world).
CascadeBox fit_cascade(const CameraFrustum& camera, float d0, float d1,
                       const glm::vec3& light_direction,
                       const std::array<glm::vec3, 8>& caster_corners, int size, FitMode mode);

// Sample distribution shadow maps' tight fit (Lauritzen, Salvi, Lefohn
// 2011): the box of a partition's samples (its pixels' world positions) in
// the light's frame, lo..hi of (x, y, depth along the light), widened on each
// side by `pad_texels` of its own texels (filter taps and the normal offset
// read around a sample; a box that ends at the samples would read its
// border there). Not square: x and y each get the map's `size` texels, so
// `texel` is the coarser of the two. Its depth range runs from the nearest of
// `caster_corners` along the light (casters outside the samples' box, towards
// the sun, still shadow them) to the samples' farthest, with a small margin.
CascadeBox fit_light_bounds(const glm::vec3& lo, const glm::vec3& hi,
                            const glm::vec3& light_direction,
                            const std::array<glm::vec3, 8>& caster_corners, int size,
                            float pad_texels);

// The box's texture coordinates of a world point: uv in [0,1]² inside the
// box, z its window depth in [0,1]; uv × size are its texel coordinates.
glm::vec3 box_coords(const CascadeBox& box, const glm::vec3& world);

// A frame's cascades: the splits, each cascade's blend band and its box.
struct CascadePlan {
  std::vector<float> splits;  // N + 1 view depths: cascade i covers [splits[i], splits[i+1]]
  // The width (view depth) of cascade i's blend band, the last part of its
  // range where it fades into cascade i + 1: blend_band × its range; 0 for
  // the last cascade.
  std::vector<float> bands;
  std::vector<CascadeBox> boxes;
};

// The cascades of one frame: the practical splits of [near, far], the bands,
// and each cascade's box fitted to its slice widened towards the camera by
// the previous cascade's band (where pixels blend into it, it must cover
// them too).
CascadePlan plan_cascades(const CameraFrustum& camera, float near_plane, float far_plane,
                          int cascades, float lambda, float blend_band,
                          const glm::vec3& light_direction,
                          const std::array<glm::vec3, 8>& caster_corners, int size, FitMode mode);

// The 8 corners of an axis-aligned box lo..hi.
std::array<glm::vec3, 8> box_corners(const glm::vec3& lo, const glm::vec3& hi);

}  // namespace sb::techniques::cascaded
