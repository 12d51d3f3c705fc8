#include "reference/pixel_rays.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"

namespace sb::reference::detail {

using core::ImageF;
using core::JobError;
using core::Scene;

namespace {

constexpr float kTfar = 1.0f - 1e-4f;  // direction = light sample - origin

// Embree's ray.valid() bound holds for every ray of a pixel when the origin's
// and the farthest light corner's coordinates stay under it; a G-buffer point
// out there (a glTF in light-years, say) fails its job instead of tripping
// Embree's asserts.
void check_ray_range(const glm::vec3& o, const glm::vec3& base, const glm::vec3& eu,
                     const glm::vec3& ev, size_t pix, int width) {
  const glm::vec3 reach = glm::abs(base) + glm::abs(eu) + glm::abs(ev);
  const float largest =
      std::max({std::fabs(o.x), std::fabs(o.y), std::fabs(o.z), reach.x, reach.y, reach.z});
  if (!(largest <= ShadowPacket::kLargest))
    throw JobError("reference: the shadow rays of pixel (" + std::to_string(pix % size_t(width)) +
                   ", " + std::to_string(pix / size_t(width)) + ") reach coordinate " +
                   std::to_string(largest) + ", beyond what Embree traces (1.8e18)");
}

}  // namespace

bool covered(const ImageF& positions, size_t pixel) { return positions.data[pixel * 4 + 3] > 0.5f; }

glm::vec2 concentric_disk(float s, float t) {
  const float a = 2.0f * s - 1.0f, b = 2.0f * t - 1.0f;
  if (a == 0.0f && b == 0.0f) return {0.0f, 0.0f};
  constexpr float kQuarterPi = 0.785398163397448f;
  float r, phi;
  if (std::fabs(a) > std::fabs(b)) {
    r = a;
    phi = kQuarterPi * (b / a);
  } else {
    r = b;
    phi = 2.0f * kQuarterPi - kQuarterPi * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}

RaySetup::RaySetup(const Scene& scene, const FlatScene& casters, const Layout& layout_,
                   const ImageF& positions_, const ImageF& normals_, uint64_t seed_)
    : layout(layout_),
      positions(positions_),
      normals(normals_),
      rtc(casters.empty() ? nullptr : casters.get()),
      offset(scene, casters),
      center(scene.light.center),
      corner(scene.light.center - scene.light.half_u - scene.light.half_v),
      eu(2.0f * scene.light.half_u),
      ev(2.0f * scene.light.half_v),
      sun(scene.light.is_sun()),
      axis(scene.light.to_sun()),
      e1(glm::length(scene.light.half_u) > 0.0f ? glm::normalize(scene.light.half_u)
                                                : glm::vec3(1, 0, 0)),
      e2(glm::length(scene.light.half_v) > 0.0f ? glm::normalize(scene.light.half_v)
                                                : glm::vec3(0, 0, 1)),
      tan_radius(std::tan(0.5f * scene.light.angular_diameter)),
      seed(seed_) {}

PixelRays::PixelRays(const RaySetup& setup) : s_(setup) { rtcInitIntersectContext(&context_); }

void PixelRays::start(size_t pix, Stream stream) {
  const float* pp = &s_.positions.data[pix * 4];
  const float* np = &s_.normals.data[pix * size_t(s_.normals.channels)];
  const glm::vec3 p(pp[0], pp[1], pp[2]);
  glm::vec3 n(np[0], np[1], np[2]);
  const float len = glm::length(n);
  if (len > 0.0f) {
    n /= len;
  } else {  // no usable normal: step towards the light instead
    const glm::vec3 to_light = s_.sun ? s_.axis : s_.center - p;
    const float d = glm::length(to_light);
    n = d > 0.0f ? to_light / d : glm::vec3(0, 1, 0);
  }
  // n is the G-buffer's geometric normal, facing the viewer: the side of the
  // surface that is seen. It is not flipped towards the light: on a closed
  // mesh that would put the origin inside the solid.
  normal_ = n;
  origin_ = p + s_.offset.at(p) * n;
  base_ = s_.corner - origin_;
  // The sun's rays run to infinity: only their origin must be in range.
  if (s_.sun)
    check_ray_range(origin_, glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f), pix,
                    s_.positions.width);
  else
    check_ray_range(origin_, base_, s_.eu, s_.ev, pix, s_.positions.width);
  packet_.reset(origin_);
  key_ = pixel_key(s_.seed, pix, uint64_t(s_.layout.spp));
  if (stream == Stream::Pilot) key_ = mix64(key_ ^ 0x3c6ef372fe94f82bull);
}

void PixelRays::trace(const uint32_t* order_index, size_t count, uint8_t* reached) {
  constexpr size_t kLanes = ShadowPacket::kLanes;
  for (size_t first = 0; first < count; first += kLanes) {
    const size_t lanes = std::min(kLanes, count - first);
    bool any = false;
    for (size_t j = 0; j < kLanes; ++j) {
      if (j >= lanes) {  // past the last sample
        packet_.deactivate(int(j));
        continue;
      }
      const uint32_t i = order_index[first + j];
      const Stratum& st = s_.layout.order[i];
      float u, v;
      sample_uv(key_, i, u, v);
      const float ls = st.s0 + u * st.ds, lt = st.t0 + v * st.dt;
      glm::vec3 d;
      float tfar = kTfar;
      if (s_.sun) {
        const glm::vec2 q = s_.tan_radius * concentric_disk(ls, lt);
        d = s_.axis + q.x * s_.e1 + q.y * s_.e2;
        tfar = std::numeric_limits<float>::infinity();
      } else {
        d = base_ + ls * s_.eu + lt * s_.ev;
      }
      // Light points below the tangent plane are occluded by the surface
      // itself, open or closed: no ray is traced for them.
      if (glm::dot(normal_, d) > 0.0f) {
        packet_.activate(int(j), d, tfar);
        any = true;
      } else {
        packet_.deactivate(int(j));
      }
    }
    if (s_.rtc != nullptr && any) rtcOccluded16(packet_.valid, s_.rtc, &context_, &packet_.ray);
    for (size_t j = 0; j < lanes; ++j) reached[first + j] = packet_.reached_light(int(j)) ? 1 : 0;
  }
}

}  // namespace sb::reference::detail
