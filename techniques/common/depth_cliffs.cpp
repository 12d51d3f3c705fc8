#include "common/depth_cliffs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace sb::techniques {

using core::Bounds;

DepthMapGeometry::DepthMapGeometry(const std::vector<float>& depth, int size, const LightFrustum& f,
                                   float reach)
    : depth_(depth),
      size_(size),
      inverse_(glm::inverse(f.view_projection)),
      light_(f.eye),
      near_(f.near_plane),
      far_(f.far_plane),
      reach_(reach) {}

float DepthMapGeometry::along(float window) const {
  return window >= 1.0f ? std::numeric_limits<float>::infinity()
                        : near_ * far_ / (far_ - window * (far_ - near_));
}

glm::vec4 DepthMapGeometry::at(int cx, int cy, float window) const {
  const float u = float(cx) / float(size_), v = float(cy) / float(size_);
  if (window >= 1.0f) {
    const glm::vec3 ray = glm::normalize(point(u, v, 0.5f) - light_);
    return glm::vec4(light_ + reach_ * ray, 1.0f);
  }
  return glm::vec4(point(u, v, window), 1.0f);
}

glm::vec3 DepthMapGeometry::point(float u, float v, float window) const {
  const glm::vec4 p =
      inverse_ * glm::vec4(2.0f * u - 1.0f, 2.0f * v - 1.0f, 2.0f * window - 1.0f, 1.0f);
  return glm::vec3(p) / p.w;
}

float past_every_receiver(const Bounds& scene_box, const glm::vec3& eye) {
  float reach = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? scene_box.hi.x : scene_box.lo.x,
                           (i & 2) ? scene_box.hi.y : scene_box.lo.y,
                           (i & 4) ? scene_box.hi.z : scene_box.lo.z);
    reach = std::max(reach, glm::length(corner - eye));
  }
  return 2.0f * reach;
}

std::vector<uint8_t> find_depth_cliffs(const DepthMapGeometry& map, float threshold) {
  const int size = map.size();
  // A cliff where the step from texel a to its neighbour b (at a + d) is
  // not the continuation of the surface on either side: b's depth is far
  // from a's extrapolated from a − d, and a's from b's extrapolated from
  // b + d. A steep but smooth surface (a sloped ground seen from the light)
  // steps every texel and is no cliff; a leaf over another is.
  const auto is_cliff_at = [&](int x, int y, int dx, int dy) {
    const float wa = map.w(x, y), wb = map.w(x + dx, y + dy);
    if (std::min(wa, wb) >= 1.0f) return false;
    if (std::max(wa, wb) >= 1.0f) return true;  // an occluder's outline
    const float za = map.along(wa), zb = map.along(wb);
    const float wa_before = map.w(x - dx, y - dy), wb_after = map.w(x + 2 * dx, y + 2 * dy);
    const float from_a = wa_before < 1.0f ? 2.0f * za - map.along(wa_before) : za;
    const float from_b = wb_after < 1.0f ? 2.0f * zb - map.along(wb_after) : zb;
    const float tolerance = threshold * std::min(za, zb);
    return std::fabs(zb - from_a) > tolerance && std::fabs(za - from_b) > tolerance &&
           std::fabs(zb - za) > tolerance;
  };
  std::vector<uint8_t> cliff(2 * size_t(size) * size_t(size), 0);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const size_t i = size_t(y) * size_t(size) + size_t(x);
      cliff[2 * i] = x + 1 < size && is_cliff_at(x, y, 1, 0);
      cliff[2 * i + 1] = y + 1 < size && is_cliff_at(x, y, 0, 1);
    }
  return cliff;
}

}  // namespace sb::techniques
