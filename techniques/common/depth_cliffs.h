#pragma once
// The depth discontinuities ("cliffs") of a depth map read back from the GPU:
// the map seen from a light point is a height field of the nearest surfaces,
// and a cliff is a step between neighbouring texels that the surface does
// not explain. Shared by the families that rebuild geometry from a map:
// shadow volumes reconstructed from it (shadow_volume/depth_map_cliffs.h)
// and the skins of soft shadow maps for linear lights
// (shadow_map/linear_light_skins.h).
//
// A step is a cliff only when it is larger than `threshold` (relative to the
// nearer depth along the light's axis) and just as far from the surface
// continued linearly from either side: the staircase of a smooth sloped
// surface is no cliff, however steep, so it does not shadow itself, while
// one leaf over another, however close, is. A texel that saw nothing
// (window depth 1) next to one that saw something is always a cliff (an
// occluder's outline).
//
// What the kit guarantees here (shadowbench::shadow_kit, installed): plain
// CPU code (no GL) on a map already read back (reading it back, in render(),
// is the caller's cost); points in world units, depths along the light's
// axis; find_depth_cliffs() costs O(size²) and returns 2·size² bytes.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "common/light_frustum.h"
#include "core/scene.h"

namespace sb::techniques {

// World points of a size×size map's texel corners at given window depths.
// `depth`: the window depths, row-major, row 0 at v = 0 (as
// glGetTextureImage returns them); 1 where nothing was drawn. The map is
// referenced, not copied.
class DepthMapGeometry {
 public:
  // Where a corner's ray meets nothing (window depth >= 1) its point is
  // `reach` from the light, not at infinity: a vertex at w = 0 leaves
  // llvmpipe's clipping with stray pixels.
  DepthMapGeometry(const std::vector<float>& depth, int size, const LightFrustum& f, float reach);

  int size() const { return size_; }
  // Texel (x, y)'s window depth; 1 outside the map.
  float w(int x, int y) const {
    if (x < 0 || y < 0 || x >= size_ || y >= size_) return 1.0f;
    return depth_[size_t(y) * size_t(size_) + size_t(x)];
  }
  // Distance along the light's axis of a window depth; +inf for 1 (empty).
  float along(float window) const;
  // The point at texel corner (cx, cy) and window depth `window` (< 1), or
  // the corner ray's point `reach` from the light for window >= 1.
  glm::vec4 at(int cx, int cy, float window) const;
  // The point at map coordinates (u, v) in [0, 1]² and window depth.
  glm::vec3 point(float u, float v, float window) const;
  const glm::vec3& light() const { return light_; }

 private:
  const std::vector<float>& depth_;
  int size_;
  glm::mat4 inverse_;
  glm::vec3 light_;
  float near_, far_;
  float reach_;
};

// How far from `eye` geometry reconstructed from a map may end where
// nothing lies behind it: twice the farthest corner of `scene_box`, past
// every receiver the camera can see.
float past_every_receiver(const core::Bounds& scene_box, const glm::vec3& eye);

// Which steps are cliffs: two flags per texel, index 2·(y·size + x) for the
// step to (x + 1, y) and 2·(y·size + x) + 1 for the step to (x, y + 1).
std::vector<uint8_t> find_depth_cliffs(const DepthMapGeometry& map, float threshold);

}  // namespace sb::techniques
