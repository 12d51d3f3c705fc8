#include "shadow_volume/volume_mesh.h"

namespace sb::techniques::shadow_volume {

VolumeVertices::Range append_volume(const Silhouette& silhouette, const glm::vec3& light, bool caps,
                                    VolumeVertices& out) {
  std::vector<glm::vec4>& v = out.vertices;
  VolumeVertices::Range range;
  range.first = int32_t(v.size());
  const auto at = [](const glm::vec3& p) { return glm::vec4(p, 1.0f); };
  const auto infinite = [&](const glm::vec3& p) { return glm::vec4(p - light, 0.0f); };
  bool has_strip = false;
  for (const auto& loop : silhouette.loops)
    for (size_t i = 0; i < loop.size(); ++i) {
      const SilhouetteVertex& a = loop[i];
      const SilhouetteVertex& b = loop[(i + 1) % loop.size()];
      v.insert(v.end(), {at(a.smooth), infinite(a.smooth), at(b.smooth), at(b.smooth),
                         infinite(a.smooth), infinite(b.smooth)});
      if (a.mesh != a.smooth || b.mesh != b.smooth) {
        // The quad b.mesh, a.mesh, a.smooth, b.smooth: its edge b.mesh → a.mesh
        // meets the near cap's a.mesh → b.mesh.
        v.insert(v.end(),
                 {at(b.mesh), at(a.mesh), at(a.smooth), at(b.mesh), at(a.smooth), at(b.smooth)});
        has_strip = true;
      }
    }
  range.sides = int32_t(v.size()) - range.first;
  if (!caps) return range;
  const std::vector<glm::vec3>& cap = silhouette.cap;
  for (const glm::vec3& p : cap) v.push_back(at(p));
  for (size_t i = 0; i < cap.size(); i += 3)
    v.insert(v.end(), {infinite(cap[i]), infinite(cap[i + 2]), infinite(cap[i + 1])});
  if (has_strip) {
    // The strip's triangles at infinity, reversed (they follow the sides
    // above: six vertices per loop edge, then six of strip where present).
    const size_t sides_end = size_t(range.first) + size_t(range.sides);
    for (size_t i = size_t(range.first); i < sides_end; i += 6) {
      if (v[i + 1].w == 0.0f) continue;  // a side quad, not a strip quad
      for (size_t t = i; t < i + 6; t += 3)
        v.insert(v.end(), {infinite(glm::vec3(v[t])), infinite(glm::vec3(v[t + 2])),
                           infinite(glm::vec3(v[t + 1]))});
    }
  }
  range.caps = int32_t(v.size()) - range.first - range.sides;
  return range;
}

}  // namespace sb::techniques::shadow_volume
