#include "shadow_volume/depth_map_cliffs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace sb::shadow {
namespace {

// Watertight by construction: every vertex is a function of a texel corner
// and a window depth only, computed the same way by every quad that uses
// it, and a cliff's side on a corner ray is split at every depth another
// cliff or cap meets that ray at (no T-junctions). Rasterisation then
// covers each pixel of a closed surface an even number of times.
class Cliffs {
 public:
  Cliffs(const std::vector<float>& depth, int size, const LightFrustum& f, float reach)
      : depth_(depth),
        size_(size),
        inverse_(glm::inverse(f.view_projection)),
        light_(f.eye),
        reach_(reach) {}

  float w(int x, int y) const {
    if (x < 0 || y < 0 || x >= size_ || y >= size_) return 1.0f;
    return depth_[size_t(y) * size_t(size_) + size_t(x)];
  }
  // The point at texel corner (cx, cy) and window depth `window` (< 1), or
  // the corner ray's point `reach` from the light for window >= 1.
  glm::vec4 at(int cx, int cy, float window) const {
    const float u = float(cx) / float(size_), v = float(cy) / float(size_);
    if (window >= 1.0f) {
      const glm::vec3 ray = glm::normalize(point(u, v, 0.5f) - light_);
      return glm::vec4(light_ + reach_ * ray, 1.0f);
    }
    return glm::vec4(point(u, v, window), 1.0f);
  }
  // The window depths strictly between `from` and `to` at which the four
  // texels around corner (cx, cy) meet its ray, in order from `from` (at
  // most four: no allocation per cliff).
  struct Depths {
    std::array<float, 4> d{};
    int n = 0;
    const float* begin() const { return d.data(); }
    const float* end() const { return d.data() + n; }
  };
  Depths between(int cx, int cy, float from, float to) const {
    Depths out;
    const float lo = std::min(from, to), hi = std::max(from, to);
    // At most four values: an insertion that keeps them ordered from
    // `from` and unique (std::sort here trips GCC 12's -Warray-bounds under
    // -O2 with sanitizers, a false positive on its 16-element threshold).
    const bool rising = from <= to;
    for (const float d : {w(cx - 1, cy - 1), w(cx, cy - 1), w(cx - 1, cy), w(cx, cy)}) {
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
  const glm::vec3& light() const { return light_; }
  glm::vec3 point(float u, float v, float window) const {
    const glm::vec4 p =
        inverse_ * glm::vec4(2.0f * u - 1.0f, 2.0f * v - 1.0f, 2.0f * window - 1.0f, 1.0f);
    return glm::vec3(p) / p.w;
  }

 private:
  const std::vector<float>& depth_;
  int size_;
  glm::mat4 inverse_;
  glm::vec3 light_;
  float reach_;
};

// A convex planar polygon as a triangle fan.
void append_fan(const std::vector<glm::vec4>& polygon, std::vector<glm::vec4>& out) {
  for (size_t i = 1; i + 1 < polygon.size(); ++i)
    out.insert(out.end(), {polygon[0], polygon[i], polygon[i + 1]});
}

}  // namespace

size_t append_depth_map_cliffs(const std::vector<float>& depth, int size, const LightFrustum& f,
                               float threshold, float reach, std::vector<glm::vec4>& out) {
  const Cliffs c(depth, size, f, reach);
  const float n = f.near_plane, fa = f.far_plane;
  const auto along = [&](float w) {  // distance along the light's axis; inf when empty
    return w >= 1.0f ? std::numeric_limits<float>::infinity() : n * fa / (fa - w * (fa - n));
  };
  std::vector<uint8_t> capped(depth.size(), 0);
  size_t cliffs = 0;
  std::vector<glm::vec4> polygon;
  // A cliff where the step from texel a to its neighbour b (at a + d) is
  // not the continuation of the surface on either side: b's depth is far
  // from a's extrapolated from a − d, and a's from b's extrapolated from
  // b + d. A steep but smooth surface (a sloped ground seen from the light)
  // steps every texel and is no cliff; a leaf over another is.
  const auto is_cliff_at = [&](int x, int y, int dx, int dy) {
    const float wa = c.w(x, y), wb = c.w(x + dx, y + dy);
    const float near_w = std::min(wa, wb);
    if (near_w >= 1.0f) return false;
    if (std::max(wa, wb) >= 1.0f) return true;  // an occluder's outline
    const float za = along(wa), zb = along(wb);
    const float wa_before = c.w(x - dx, y - dy), wb_after = c.w(x + 2 * dx, y + 2 * dy);
    const float from_a = wa_before < 1.0f ? 2.0f * za - along(wa_before) : za;
    const float from_b = wb_after < 1.0f ? 2.0f * zb - along(wb_after) : zb;
    const float tolerance = threshold * std::min(za, zb);
    return std::fabs(zb - from_a) > tolerance && std::fabs(za - from_b) > tolerance &&
           std::fabs(zb - za) > tolerance;
  };
  const auto index = [&](int x, int y) { return size_t(y) * size_t(size) + size_t(x); };
  // Each texel's step to its +x (slot 0) and +y (slot 1) neighbour, judged
  // once. The texels at a cliff's top get caps; between two capped texels
  // every step is drawn, however small, or the two caps would leave a slit.
  std::vector<uint8_t> cliff(2 * depth.size(), 0);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (const auto [dx, dy] : {std::array<int, 2>{1, 0}, std::array<int, 2>{0, 1}}) {
        if (x + dx >= size || y + dy >= size || !is_cliff_at(x, y, dx, dy)) continue;
        cliff[2 * index(x, y) + size_t(dy)] = 1;
        capped[c.w(x, y) <= c.w(x + dx, y + dy) ? index(x, y) : index(x + dx, y + dy)] = 1;
      }
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
    for (const float d : c.between(q[0], q[1], near_w, far_w))
      polygon.push_back(c.at(q[0], q[1], d));
    polygon.push_back(c.at(q[0], q[1], far_w));
    polygon.push_back(c.at(p[0], p[1], far_w));
    for (const float d : c.between(p[0], p[1], far_w, near_w))
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

}  // namespace sb::shadow
