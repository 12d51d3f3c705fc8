#include "shadow_map/linear_light_skins.h"

#include <algorithm>
#include <cstdint>

#include "common/depth_cliffs.h"

namespace sb::techniques::shadow_map {

size_t append_linear_light_skins(const std::vector<float>& depth, int size, const LightFrustum& f,
                                 float threshold, float reach, std::vector<SkinVertex>& out) {
  const DepthMapGeometry map(depth, size, f, reach);
  const std::vector<uint8_t> cliff = find_depth_cliffs(map, threshold);
  size_t count = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (int slot = 0; slot < 2; ++slot) {
        if (!cliff[2 * (size_t(y) * size_t(size) + size_t(x)) + size_t(slot)]) continue;
        const int dx = slot == 0 ? 1 : 0, dy = slot;
        const float wa = map.w(x, y), wb = map.w(x + dx, y + dy);
        const float near_w = std::min(wa, wb), far_w = std::max(wa, wb);
        // The shared side runs from corner (x + dx, y + dy) to (x + 1, y + 1).
        const int px = x + dx, py = y + dy, qx = x + 1, qy = y + 1;
        const SkinVertex p_near{map.at(px, py, near_w), 0.0f}, q_near{map.at(qx, qy, near_w), 0.0f};
        const SkinVertex p_far{map.at(px, py, far_w), 1.0f}, q_far{map.at(qx, qy, far_w), 1.0f};
        out.insert(out.end(), {p_near, q_near, q_far, p_near, q_far, p_far});
        ++count;
      }
  return count;
}

}  // namespace sb::techniques::shadow_map
