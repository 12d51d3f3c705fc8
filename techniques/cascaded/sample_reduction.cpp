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

// The covered pixel's world position (w = 1) and its view depth; w = 0 on background.
vec4 covered_pixel(out float depth) {
  depth = 0.0;
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(px, size))) return vec4(0.0);
  vec4 p = texelFetch(position_tex, px, 0);
  if (p.w == 0.0) return vec4(0.0);
  // In the stated order, unfused: the CPU's view_depth() gets the same float.
  precise float d = -(((view_row.x * p.x + view_row.y * p.y) + view_row.z * p.z) + view_row.w);
  depth = d;
  return vec4(p.xyz, 1.0);
}
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
  float d;
  if (covered_pixel(d).w != 0.0) {
    uint k = ordered_key(d);
    atomicMin(group_min, k);
    atomicMax(group_max, k);
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
uniform float partition_end[8];
uniform float partition_band[8];
uniform float seam;
// Per partition and axis (x, y, depth along the light): the group's min and max keys.
shared uint group_min[24];
shared uint group_max[24];

void add(int i, vec3 q) {
  for (int k = 0; k < 3; ++k) {
    uint key = ordered_key(q[k]);
    atomicMin(group_min[3 * i + k], key);
    atomicMax(group_max[3 * i + k], key);
  }
}

void main() {
  uint t = gl_LocalInvocationIndex;
  if (t < 24u) {
    group_min[t] = 0xFFFFFFFFu;
    group_max[t] = 0u;
  }
  barrier();
  float d;
  vec4 p = covered_pixel(d);
  if (p.w != 0.0) {
    vec4 l = light_view * p;
    vec3 q = vec3(l.xy, -l.z);
    // The partition as the lookup selects it.
    int i = 0;
    while (i < partition_count - 1 && d > partition_end[i]) ++i;
    add(i, q);
    // Where the lookup also reads the next partition (its blend band), or
    // its own rounding of d may cross an end: the neighbour must cover it too.
    if (i + 1 < partition_count &&
        d > partition_end[i] - partition_band[i] - seam * partition_end[i])
      add(i + 1, q);
    if (i > 0 && d <= partition_end[i - 1] * (1.0 + seam)) add(i - 1, q);
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
  glDispatchCompute(GLuint((width + 15) / 16), GLuint((height + 15) / 16), 1);
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
  bounds_program_.set("partition_end", ends);
  bounds_program_.set("partition_band", bands);
  bounds_program_.set("seam", seam);
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
