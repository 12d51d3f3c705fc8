#pragma once
// One rtcOccluded16 call's worth of shadow rays from one surface point
// (internal; exposed so the tests can check the lane invariants).
//
// Why inactive lanes get tfar = -inf and a finite direction, not only
// valid = 0: Embree serves rtcOccluded16 natively only on its avx512
// kernels. On avx2 and below it hands the packet to its ray-stream filter,
// which never reads the valid mask: it skips a lane only when tnear > tfar or
// tfar < 0 (an "already occluded" ray) and asserts that every lane it keeps
// has a finite origin and direction (Debian's Embree keeps its asserts, so a
// stale lane aborted the process). The native kernels read the mask and also
// drop lanes with tfar < 0. So a lane with valid = 0, tfar = -inf and a
// finite direction is skipped on every ISA, and the mask stays right for the
// kernels that read it.
#include <embree3/rtcore.h>

#include <cmath>
#include <cstddef>
#include <glm/glm.hpp>
#include <limits>

namespace sb::reference::detail {

struct ShadowPacket {
  static constexpr int kLanes = 16;
  // Embree's ray.valid(): |org| and |dir| components at most this.
  static constexpr float kLargest = 1.844e18f;

  RTCRay16 ray;
  alignas(64) int valid[kLanes];

  // Every lane inactive, all from origin o.
  void reset(const glm::vec3& o) {
    for (int j = 0; j < kLanes; ++j) {
      ray.org_x[j] = o.x;
      ray.org_y[j] = o.y;
      ray.org_z[j] = o.z;
      ray.time[j] = 0.0f;
      ray.mask[j] = 0xffffffffu;
      ray.id[j] = unsigned(j);
      ray.flags[j] = 0;
      deactivate(j);
    }
  }

  // Lane j skipped by every kernel (see the top of this file).
  void deactivate(int j) {
    valid[j] = 0;
    ray.tnear[j] = 0.0f;
    ray.tfar[j] = -std::numeric_limits<float>::infinity();
    ray.dir_x[j] = 0.0f;
    ray.dir_y[j] = 0.0f;
    ray.dir_z[j] = 1.0f;
  }

  // Lane j traces from the origin along d for t in [0, tfar].
  void activate(int j, const glm::vec3& d, float tfar) {
    valid[j] = -1;
    ray.tnear[j] = 0.0f;
    ray.tfar[j] = tfar;
    ray.dir_x[j] = d.x;
    ray.dir_y[j] = d.y;
    ray.dir_z[j] = d.z;
  }

  // After rtcOccluded16: an active lane that hit nothing keeps tfar >= 0
  // (occluded rays come back with -inf).
  bool reached_light(int j) const { return valid[j] != 0 && ray.tfar[j] >= 0.0f; }
};

}  // namespace sb::reference::detail
