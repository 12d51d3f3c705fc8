#include "cascaded/sample_reduction.h"

#include <array>
#include <cstring>
#include <string>

#include "gl/debug.h"

namespace sb::techniques::cascaded {

namespace {

// What both passes share: the inputs, the key and the pixel's view depth.
const char* const kReductionPrelude = R"glsl(#version 450 core
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = 0) uniform sampler2D position_tex;
layout(std430, binding = 0) buffer Reduction { uint keys[]; };
uniform ivec2 size;
// The camera's view matrix's third row: view depth is minus its dot with (p, 1).
uniform vec4 view_row;

uint ordered_key(float f) {
  uint b = floatBitsToUint(f);
  return (b & 0x80000000u) != 0u ? ~b : (b | 0x80000000u);
}

// Each invocation reduces a kSpan×kSpan block of pixels in registers first,
// then touches shared memory once: the atomics, not the pixels, cost most.
const int kSpan = 4;

// Pixel px's world position (w = 1) and its view depth; w = 0 on background
// and outside the image.
vec4 covered_pixel(ivec2 px, out float depth) {
  depth = 0.0;
  if (any(greaterThanEqual(px, size))) return vec4(0.0);
  vec4 p = texelFetch(position_tex, px, 0);
  if (p.w == 0.0) return vec4(0.0);
  // In the stated order, unfused: the CPU's view_depth() gets the same float.
  precise float d = -(((view_row.x * p.x + view_row.y * p.y) + view_row.z * p.z) + view_row.w);
  depth = d;
  return vec4(p.xyz, 1.0);
}

ivec2 block_origin() { return ivec2(gl_GlobalInvocationID.xy) * kSpan; }
)glsl";

const char* const kDepthRange = R"glsl(
shared uint group_min;
shared uint group_max;
void main() {
  if (gl_LocalInvocationIndex == 0u) {
    group_min = 0xFFFFFFFFu;
    group_max = 0u;
  }
  barrier();
  float lo = 3.4e38, hi = -3.4e38;
  for (int y = 0; y < kSpan; ++y)
    for (int x = 0; x < kSpan; ++x) {
      float d;
      if (covered_pixel(block_origin() + ivec2(x, y), d).w != 0.0) {
        lo = min(lo, d);
        hi = max(hi, d);
      }
    }
  // min and max of floats are exact: the keys of lo and hi are the block's extremes.
  if (lo <= hi) {
    atomicMin(group_min, ordered_key(lo));
    atomicMax(group_max, ordered_key(hi));
  }
  barrier();
  if (gl_LocalInvocationIndex == 0u && group_min <= group_max) {
    atomicMin(keys[0], group_min);
    atomicMax(keys[1], group_max);
  }
}
)glsl";

const char* const kLightBounds = R"glsl(
uniform mat4 light_view;
uniform int partition_count;
// Partition i takes the pixels with depth in (partition_lo[i], partition_hi[i]]:
// its own range, widened (light_bounds() on the CPU says how).
uniform float partition_lo[8];
uniform float partition_hi[8];
// Per partition and axis (x, y, depth along the light): the group's min and max keys.
shared uint group_min[24];
shared uint group_max[24];

void main() {
  uint t = gl_LocalInvocationIndex;
  if (t < 24u) {
    group_min[t] = 0xFFFFFFFFu;
    group_max[t] = 0u;
  }
  // The invocation's own bounds per partition, merged into the group's at
  // the end. Indexed only by constant-bound loops, which unroll into
  // registers (an index per pixel would make the arrays memory).
  vec3 own_lo[8] = vec3[8](vec3(3.4e38), vec3(3.4e38), vec3(3.4e38), vec3(3.4e38), vec3(3.4e38),
                           vec3(3.4e38), vec3(3.4e38), vec3(3.4e38));
  vec3 own_hi[8] = vec3[8](vec3(-3.4e38), vec3(-3.4e38), vec3(-3.4e38), vec3(-3.4e38),
                           vec3(-3.4e38), vec3(-3.4e38), vec3(-3.4e38), vec3(-3.4e38));
  barrier();
  for (int y = 0; y < kSpan; ++y)
    for (int x = 0; x < kSpan; ++x) {
      float d;
      vec4 p = covered_pixel(block_origin() + ivec2(x, y), d);
      if (p.w == 0.0) continue;
      vec4 l = light_view * p;
      vec3 q = vec3(l.xy, -l.z);
      for (int i = 0; i < 8; ++i)
        if (i < partition_count && d > partition_lo[i] && d <= partition_hi[i]) {
          own_lo[i] = min(own_lo[i], q);
          own_hi[i] = max(own_hi[i], q);
        }
    }
  for (int i = 0; i < 8; ++i) {
    if (i >= partition_count || own_lo[i].x > own_hi[i].x) continue;
    for (int k = 0; k < 3; ++k) {
      atomicMin(group_min[3 * i + k], ordered_key(own_lo[i][k]));
      atomicMax(group_max[3 * i + k], ordered_key(own_hi[i][k]));
    }
  }
  barrier();
  if (t < uint(3 * partition_count) && group_min[t] <= group_max[t]) {
    uint i = t / 3u, k = t % 3u;
    atomicMin(keys[2u + 6u * i + k], group_min[t]);
    atomicMax(keys[2u + 6u * i + 3u + k], group_max[t]);
  }
}
)glsl";

glm::vec4 view_row(const glm::mat4& view) {
  return {view[0][2], view[1][2], view[2][2], view[3][2]};
}

void dispatch(const gl::Program& program, const gl::Buffer& buffer, GLuint position_texture,
              int width, int height, const glm::mat4& view) {
  program.set("size", glm::ivec2(width, height));
  program.set("view_row", view_row(view));
  program.use();
  glBindTextureUnit(0, position_texture);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer.get());
  // 16×16 invocations of 4×4 pixels each (kSpan in the GLSL).
  glDispatchCompute(GLuint((width + 63) / 64), GLuint((height + 63) / 64), 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace

unsigned ordered_key(float f) {
  unsigned b = 0;
  std::memcpy(&b, &f, 4);
  return (b & 0x80000000u) != 0u ? ~b : (b | 0x80000000u);
}

float from_ordered_key(unsigned key) {
  const unsigned b = (key & 0x80000000u) != 0u ? (key & 0x7FFFFFFFu) : ~key;
  float f = 0.0f;
  std::memcpy(&f, &b, 4);
  return f;
}

float view_depth(const glm::mat4& view, const glm::vec3& p) {
  const glm::vec4 r = view_row(view);
  // The shader's order; x86-64 without -march has no FMA to fuse them into.
  float s = r.x * p.x;
  s = s + r.y * p.y;
  s = s + r.z * p.z;
  s = s + r.w;
  return -s;
}

SampleReduction::SampleReduction(bool make) {
  if (!make) return;
  depth_program_ =
      gl::Program::compute("sdsm_depth_range", std::string(kReductionPrelude) + kDepthRange);
  bounds_program_ =
      gl::Program::compute("sdsm_light_bounds", std::string(kReductionPrelude) + kLightBounds);
  buffer_ = gl::make_buffer(kBufferBytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
  gl::throw_if_errors("creating the sample distribution reductions");
}

glm::vec2 SampleReduction::depth_range(GLuint position_texture, int width, int height,
                                       const glm::mat4& view) {
  const std::array<unsigned, 2> start = {0xFFFFFFFFu, 0u};
  glNamedBufferSubData(buffer_.get(), 0, sizeof(start), start.data());
  dispatch(depth_program_, buffer_, position_texture, width, height, view);
  std::array<unsigned, 2> keys{};
  glGetNamedBufferSubData(buffer_.get(), 0, sizeof(keys), keys.data());
  if (keys[0] > keys[1]) return {1.0f, 0.0f};
  return {from_ordered_key(keys[0]), from_ordered_key(keys[1])};
}

std::vector<LightBounds> SampleReduction::light_bounds(GLuint position_texture, int width,
                                                       int height, const glm::mat4& view,
                                                       const glm::mat4& light_view,
                                                       const std::vector<float>& ends,
                                                       const std::vector<float>& bands,
                                                       float seam) {
  const int n = int(ends.size());
  std::array<unsigned, 6 * kMaxPartitions> keys{};
  for (int i = 0; i < 6 * n; ++i) keys[size_t(i)] = i % 6 < 3 ? 0xFFFFFFFFu : 0u;
  const GLsizeiptr bytes = GLsizeiptr(sizeof(unsigned)) * 6 * n;
  glNamedBufferSubData(buffer_.get(), 8, bytes, keys.data());
  bounds_program_.set("light_view", light_view);
  bounds_program_.set("partition_count", n);
  // The lookup reads partition i for depths in (ends[i-1], ends[i]], and
  // i + 1 too in i's last bands[i]; its own rounding of a depth may cross an
  // end by `seam`. Partition i's pixels must hold all of them.
  std::vector<float> lo(size_t(n), -3.4e38f), hi(size_t(n), 3.4e38f);
  for (int i = 1; i < n; ++i) {
    const float end = ends[size_t(i) - 1];
    lo[size_t(i)] = end - bands[size_t(i) - 1] - seam * end;
    hi[size_t(i) - 1] = end * (1.0f + seam);
  }
  bounds_program_.set("partition_lo", lo);
  bounds_program_.set("partition_hi", hi);
  dispatch(bounds_program_, buffer_, position_texture, width, height, view);
  glGetNamedBufferSubData(buffer_.get(), 8, bytes, keys.data());
  std::vector<LightBounds> out(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const unsigned* k = &keys[size_t(6 * i)];
    if (k[0] > k[3]) {
      out[size_t(i)] = {glm::vec3(1.0f), glm::vec3(0.0f)};
      continue;
    }
    for (int a = 0; a < 3; ++a) {
      out[size_t(i)].lo[a] = from_ordered_key(k[a]);
      out[size_t(i)].hi[a] = from_ordered_key(k[3 + a]);
    }
  }
  return out;
}

}  // namespace sb::techniques::cascaded
