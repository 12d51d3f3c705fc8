#include "shadow_volume/depth_map_cliffs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "common/depth_cliffs.h"

namespace sb::techniques::shadow_volume {
namespace {

// Watertight by construction: every vertex is a function of a texel corner
// and a window depth only (DepthMapGeometry::at), computed the same way by
// every quad that uses it, and a cliff's side on a corner ray is split at
// every depth another cliff or cap meets that ray at (no T-junctions).
// Rasterisation then covers each pixel of a closed surface an even number
// of times.
//
// The window depths strictly between `from` and `to` at which the four
// texels around corner (cx, cy) meet its ray, in order from `from` (at most
// four: no allocation per cliff).
struct Depths {
  std::array<float, 4> d{};
  int n = 0;
  const float* begin() const { return d.data(); }
  const float* end() const { return d.data() + n; }
};
Depths between(const DepthMapGeometry& c, int cx, int cy, float from, float to) {
  Depths out;
  const float lo = std::min(from, to), hi = std::max(from, to);
  // At most four values: an insertion that keeps them ordered from
  // `from` and unique (std::sort here trips GCC 12's -Warray-bounds under
  // -O2 with sanitizers, a false positive on its 16-element threshold).
  const bool rising = from <= to;
  for (const float d : {c.w(cx - 1, cy - 1), c.w(cx, cy - 1), c.w(cx - 1, cy), c.w(cx, cy)}) {
    if (!(d > lo && d < hi && d < 1.0f)) continue;
    int i = out.n;
    bool repeated = false;
    for (int k = 0; k < out.n; ++k) repeated = repeated || out.d[size_t(k)] == d;
    if (repeated) continue;
    while (i > 0 && (rising ? out.d[size_t(i - 1)] > d : out.d[size_t(i - 1)] < d)) {
      out.d[size_t(i)] = out.d[size_t(i - 1)];
      --i;
    }
    out.d[size_t(i)] = d;
    ++out.n;
  }
  return out;
}

// A convex planar polygon as a triangle fan.
void append_fan(const std::vector<glm::vec4>& polygon, std::vector<glm::vec4>& out) {
  for (size_t i = 1; i + 1 < polygon.size(); ++i)
    out.insert(out.end(), {polygon[0], polygon[i], polygon[i + 1]});
}

}  // namespace

size_t append_depth_map_cliffs(const std::vector<float>& depth, int size, const LightFrustum& f,
                               float threshold, float reach, std::vector<glm::vec4>& out) {
  const DepthMapGeometry c(depth, size, f, reach);
  const std::vector<uint8_t> cliff = find_depth_cliffs(c, threshold);
  const auto index = [&](int x, int y) { return size_t(y) * size_t(size) + size_t(x); };
  // The texels at a cliff's top get caps; between two capped texels every
  // step is drawn, however small, or the two caps would leave a slit.
  std::vector<uint8_t> capped(depth.size(), 0);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (const auto [dx, dy] : {std::array<int, 2>{1, 0}, std::array<int, 2>{0, 1}}) {
        if (!cliff[2 * index(x, y) + size_t(dy)]) continue;
        capped[c.w(x, y) <= c.w(x + dx, y + dy) ? index(x, y) : index(x + dx, y + dy)] = 1;
      }
  size_t cliffs = 0;
  std::vector<glm::vec4> polygon;
  // Texel (x, y) and its neighbour (x + dx, y + dy) share the side from
  // corner (x + dx, y + dy) to corner (x + 1, y + 1).
  const auto consider = [&](int x, int y, int dx, int dy) {
    const float wa = c.w(x, y), wb = c.w(x + dx, y + dy);
    const bool a_near = wa <= wb;
    const float near_w = a_near ? wa : wb, far_w = a_near ? wb : wa;
    const bool step_between_caps = capped[index(x, y)] && capped[index(x + dx, y + dy)] && wa != wb;
    if (near_w >= 1.0f || (!step_between_caps && !cliff[2 * index(x, y) + size_t(dy)])) return;
    int p[2] = {x + dx, y + dy}, q[2] = {x + 1, y + 1};
    // Out of the shadow: from the nearer texel's centre towards the farther's.
    const float texel = 1.0f / float(size);
    const glm::vec2 centre_a((float(x) + 0.5f) * texel, (float(y) + 0.5f) * texel);
    const glm::vec2 centre_b((float(x + dx) + 0.5f) * texel, (float(y + dy) + 0.5f) * texel);
    const glm::vec2 near_c = a_near ? centre_a : centre_b, far_c = a_near ? centre_b : centre_a;
    const glm::vec3 outwards =
        c.point(far_c.x, far_c.y, near_w) - c.point(near_c.x, near_c.y, near_w);
    const glm::vec3 a = glm::vec3(c.at(p[0], p[1], near_w)),
                    b = glm::vec3(c.at(q[0], q[1], near_w));
    if (glm::dot(glm::cross(b - a, a - c.light()), outwards) < 0.0f) {
      std::swap(p[0], q[0]);
      std::swap(p[1], q[1]);
    }
    // P_near, Q_near, down Q's ray, Q_far, P_far, up P's ray.
    polygon.clear();
    polygon.push_back(c.at(p[0], p[1], near_w));
    polygon.push_back(c.at(q[0], q[1], near_w));
    for (const float d : between(c, q[0], q[1], near_w, far_w))
      polygon.push_back(c.at(q[0], q[1], d));
    polygon.push_back(c.at(q[0], q[1], far_w));
    polygon.push_back(c.at(p[0], p[1], far_w));
    for (const float d : between(c, p[0], p[1], far_w, near_w))
      polygon.push_back(c.at(p[0], p[1], d));
    append_fan(polygon, out);
    ++cliffs;
  };
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      if (x + 1 < size) consider(x, y, 1, 0);
      if (y + 1 < size) consider(x, y, 0, 1);
    }
  // The caps, facing the light. A camera ray
  // can enter the space behind such a texel through its top without
  // meeting the occluder (the texel is only partly covered); elsewhere the
  // occluder itself stands in front of the cap (the depth pass's bias puts
  // every cap behind its surface), so those caps are never crossed. A cap's
  // side meets a cliff's top edge exactly (the same corners and depth).
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      if (!capped[size_t(y) * size_t(size) + size_t(x)]) continue;
      const float d = c.w(x, y);
      glm::vec4 c00 = c.at(x, y, d), c10 = c.at(x + 1, y, d);
      const glm::vec4 c11 = c.at(x + 1, y + 1, d);
      glm::vec4 c01 = c.at(x, y + 1, d);
      const glm::vec3 e = glm::vec3(c00);
      if (glm::dot(glm::cross(glm::vec3(c10) - e, glm::vec3(c11) - e), c.light() - e) < 0.0f)
        std::swap(c10, c01);
      out.insert(out.end(), {c00, c10, c11, c00, c11, c01});
    }
  return cliffs;
}

}  // namespace sb::techniques::shadow_volume
