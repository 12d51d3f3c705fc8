#pragma once
// The shadow rays of one G-buffer pixel towards its light samples (internal
// to the reference; the uniform and the adaptive sampler share it, so that a
// pixel the adaptive one refines to the full count traces exactly the
// uniform reference's rays and gets its very value).
//
// Sample i of a pixel is stratum layout.order[i] drawn with sample_uv(key, i),
// key = pixel_key(seed, pixel, spp) (stratify.h): the uniform reference
// traces i = 0..spp-1; the adaptive one a nested subset (adaptive.h), and
// its pilot draws from a second, independent stream.
#include <embree3/rtcore.h>

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>

#include "core/image.h"
#include "core/scene.h"
#include "reference/ray_offset.h"
#include "reference/shadow_packet.h"
#include "reference/stratify.h"

namespace sb::reference::detail {

// What every pixel's rays share: the light, the casters, the sample layout.
struct RaySetup {
  RaySetup(const core::Scene& scene, const FlatScene& casters, const Layout& layout,
           const core::ImageF& positions, const core::ImageF& normals, uint64_t seed);
  const Layout& layout;
  const core::ImageF& positions;  // RGBA32F, w > 0.5 on a surface
  const core::ImageF& normals;    // 3 or 4 channels
  RTCScene rtc;                   // null without casters: only the horizon test remains
  RayOffset offset;
  glm::vec3 center;          // the light's
  glm::vec3 corner, eu, ev;  // a local light: corner + s*eu + t*ev
  // The sun: a sample (s, t) is the direction axis + tan_radius·(x·e1 +
  // y·e2), (x, y) = concentric_disk(s, t), on the plane at unit distance
  // along the axis (core::AreaLight's definition of the sun's V).
  bool sun;
  glm::vec3 axis, e1, e2;
  float tan_radius;
  uint64_t seed;
};

bool covered(const core::ImageF& positions, size_t pixel);

// Shirley and Chiu's concentric map of the unit square onto the unit disk:
// it keeps areas, so strata of the square become equal-area strata of the
// disk.
glm::vec2 concentric_disk(float s, float t);

// Which of a pixel's two independent sample streams: the estimate's (the
// uniform reference's samples) or the adaptive reference's pilot's, which
// decides how many samples the estimate takes and is never part of it.
enum class Stream : uint8_t { Estimate, Pilot };

// One thread's tracer: start() a pixel, then trace() any of its samples.
class PixelRays {
 public:
  explicit PixelRays(const RaySetup& setup);

  // The pixel's ray origin and sample stream. Throws JobError when its rays
  // reach beyond what Embree can trace.
  void start(size_t pixel, Stream stream = Stream::Estimate);
  // reached[k] = 1 when sample order_index[k] reaches the light (samples
  // below the surface's tangent plane never do, and trace no ray).
  void trace(const uint32_t* order_index, size_t count, uint8_t* reached);
  // The started pixel's ray origin and unit normal.
  const glm::vec3& origin() const { return origin_; }
  const glm::vec3& normal() const { return normal_; }

 private:
  const RaySetup& s_;
  RTCIntersectContext context_;
  ShadowPacket packet_;
  glm::vec3 origin_{0.0f}, normal_{0.0f}, base_{0.0f};
  uint64_t key_ = 0;
};

}  // namespace sb::reference::detail
