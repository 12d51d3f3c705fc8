#pragma once
// raytraced's casters on the GPU: the hierarchy (shadow_bvh.h) and what its
// shaders test, in shader storage buffers made through gl::make_buffer (so
// technique.gpu_bytes counts them). Built in prepare(): scene geometry and
// the leaf size only.
//
//   binding 0  nodes      2 vec4 per node, depth-first: (lo, first-or-skip),
//                         (hi, count); an inner node (count 0) holds its skip,
//                         the node after its subtree (a stackless walk)
//   binding 1  triangles  3 vec4 per triangle in leaf order: the corners,
//                         corner a's w the triangle's entry in `masks` as
//                         uint bits (0xffffffff: opaque)
//   binding 2  masks      per alpha-tested triangle 2 vec4: (uv_a, uv_b),
//                         (uv_c, texture, cutoff)
//   binding 3  textures   per mask texture 4 uints: byte offset, width, height, 0
//   binding 4  alphas     the mask textures' alpha bytes, 4 a uint, row-major,
//                         row 0 at v = 0 (core::sample_alpha's texels)
#include <cstdint>
#include <vector>

#include "core/scene.h"
#include "gl/objects.h"
#include "raytraced/shadow_bvh.h"

namespace sb::techniques::raytraced {

// The caster triangles of `scene` (meshes with casts_shadow) and, for each,
// its alpha mask (-1: opaque), on the CPU.
struct CasterSet {
  std::vector<BvhTriangle> triangles;
  struct Mask {
    glm::vec2 uv[3];
    int texture;  // into Scene::textures
    float cutoff;
  };
  std::vector<int> mask_of;  // per triangle: index into masks, or -1
  std::vector<Mask> masks;
};
CasterSet collect_casters(const core::Scene& scene);

class GpuCasters {
 public:
  GpuCasters() = default;
  GpuCasters(const core::Scene& scene, int leaf_size);
  // Binds the five buffers to bindings 0..4.
  void bind() const;
  bool empty() const { return node_count_ == 0; }
  int depth() const { return depth_; }

 private:
  gl::Buffer nodes_, triangles_, masks_, textures_, alphas_;
  size_t node_count_ = 0;
  int depth_ = 0;
};

}  // namespace sb::techniques::raytraced
