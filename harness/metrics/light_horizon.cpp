#include "metrics/light_horizon.h"

namespace sb::metrics {

using core::AreaLight;
using core::ImageF;

std::vector<LightHorizon> classify_light_horizon(const ImageF& positions, const ImageF& normals,
                                                 const AreaLight& light) {
  std::vector<LightHorizon> out(positions.pixel_count(), LightHorizon::Background);
  // A plane cuts a convex polygon exactly when its corners lie on both sides.
  const glm::vec3 corners[4] = {light.point(0, 0), light.point(1, 0), light.point(0, 1),
                                light.point(1, 1)};
  for (size_t i = 0; i < out.size(); ++i) {
    if (positions.data[i * 4 + 3] == 0.0f) continue;
    const glm::vec3 p(positions.data[i * 4], positions.data[i * 4 + 1], positions.data[i * 4 + 2]);
    const glm::vec3 n(normals.data[i * 3], normals.data[i * 3 + 1], normals.data[i * 3 + 2]);
    if (light.is_sun()) {  // at infinity: only the normal matters
      const int side = core::sun_side(light, glm::dvec3(n));
      out[i] = side > 0 ? LightHorizon::Above : side < 0 ? LightHorizon::Below : LightHorizon::Cuts;
      continue;
    }
    int above = 0;
    for (const auto& c : corners) above += glm::dot(n, c - p) > 0.0f ? 1 : 0;
    out[i] = above == 4   ? LightHorizon::Above
             : above == 0 ? LightHorizon::Below
                          : LightHorizon::Cuts;
  }
  return out;
}

std::vector<uint8_t> horizon_mask(const std::vector<LightHorizon>& horizon, LightHorizon which) {
  std::vector<uint8_t> mask(horizon.size(), 0);
  for (size_t i = 0; i < horizon.size(); ++i) mask[i] = horizon[i] == which ? 1 : 0;
  return mask;
}

}  // namespace sb::metrics
