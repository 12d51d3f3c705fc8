#pragma once
// Sample distribution shadow maps' reductions (Lauritzen, Salvi, Lefohn
// 2011) over the G-buffer's world positions, on the GPU, two compute passes:
//   depth_range()   the min and max view depth of the covered pixels (w != 0),
//   light_bounds()  per partition (view depths between given splits), the
//                   axis-aligned box of its pixels in the sun's frame.
// Each result is read back to the CPU (a few dozen bytes; the read waits for
// the pass): the partitions and their ortho boxes are fitted there.
//
// Every covered pixel's view depth is computed in one stated order, without
// fused multiply-adds (`precise`): d = -(((r.x·p.x + r.y·p.y) + r.z·p.z) + r.w),
// r the view matrix's third row, so that a CPU doing the same float
// operations gets the same depths and so the same min and max (view_depth()).
//
//   GL     made in construction (two compute programs, one metered buffer of
//          kBufferBytes); each call binds the position texture to unit 0 and
//          the buffer to SSBO binding 0, and leaves them bound;
//   cost   per call one pass over width×height pixels (workgroups of 16×16
//          invocations, each reducing 4×4 pixels in registers, then one
//          shared-memory atomic per invocation and value, one global atomic
//          per workgroup and value), then a read-back of 2 (depth) or
//          6 × partitions (bounds) uints.
#include <glm/glm.hpp>
#include <vector>

#include "gl/objects.h"
#include "gl/program.h"

namespace sb::techniques::cascaded {

// The order-preserving float-to-uint key the passes reduce with atomicMin and
// atomicMax (negative floats reversed below the positive ones), and its inverse.
unsigned ordered_key(float f);
float from_ordered_key(unsigned key);

// A pixel's view depth as the reduction computes it (see above).
float view_depth(const glm::mat4& view, const glm::vec3& world);

// A partition's pixels in the light's frame: lo..hi of (x, y, depth along
// the light); empty (lo > hi) when no pixel falls in it.
struct LightBounds {
  glm::vec3 lo{0.0f};
  glm::vec3 hi{0.0f};
  bool empty() const { return lo.x > hi.x; }
};

class SampleReduction {
 public:
  static constexpr int kMaxPartitions = 8;
  // Two depth keys, then 6 keys (lo.xyz, hi.xyz) per partition.
  static constexpr long kBufferBytes = (2 + 6 * kMaxPartitions) * 4;

  SampleReduction() = default;
  // Compiles the programs and makes the buffer (needs a GL 4.5 context).
  explicit SampleReduction(bool make);

  // The min (x) and max (y) view depth of the covered pixels of the
  // width×height position texture; x > y when no pixel is covered.
  glm::vec2 depth_range(GLuint position_texture, int width, int height, const glm::mat4& view);

  // Per partition i (view depth in (ends[i-1], ends[i]], the first from 0,
  // the last to infinity, as the lookup selects), the light-frame box of
  // its pixels, `light_view` the sun's rotation (cascade_fit.h's
  // light_rotation). A pixel also counts in partition i + 1 when its depth
  // is in partition i's last `bands[i]` (the blend band, where it is looked
  // up in both), and in both partitions when within `seam` (relative) of
  // their common end (the lookup's own depth may round across it). Needs
  // each band under its partition's range (blend_band <= 0.5 holds it).
  std::vector<LightBounds> light_bounds(GLuint position_texture, int width, int height,
                                        const glm::mat4& view, const glm::mat4& light_view,
                                        const std::vector<float>& ends,
                                        const std::vector<float>& bands, float seam);

 private:
  gl::Program depth_program_;
  gl::Program bounds_program_;
  gl::Buffer buffer_;
};

}  // namespace sb::techniques::cascaded
