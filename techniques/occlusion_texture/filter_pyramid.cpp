#include "occlusion_texture/filter_pyramid.h"

#include <stdexcept>
#include <string>

#include "gl/debug.h"

namespace sb::techniques::occlusion_texture {
namespace {

constexpr int kGroup = 8;  // compute work-group side

// Level k from level k − 1 (both layers of one array): the mean of the four
// boxes of side 2^(k−1) that tile the box of side 2^k starting at the texel;
// boxes reaching past the texture's edge count the texels inside only,
// taken as 0 outside (the light beyond the occlusion texture is unoccluded).
const char* const kNBufferLevel = R"(#version 450 core
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2DArray previous;  // level k − 1 in layer `layer` − 1
layout(binding = 0, rgba16f) uniform writeonly image2DArray levels;
uniform int layer;
uniform int half_side;  // 2^(k−1)
uniform int size;
vec4 read(ivec2 p) {
  if (any(greaterThanEqual(p, ivec2(size)))) return vec4(0.0);
  return texelFetch(previous, ivec3(p, layer - 1), 0);
}
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(size)))) return;
  vec4 sum = read(p) + read(p + ivec2(half_side, 0)) + read(p + ivec2(0, half_side)) +
             read(p + ivec2(half_side));
  imageStore(levels, ivec3(p, layer), 0.25 * sum);
}
)";

// Level 0 of the N-buffers: the source itself.
const char* const kNBufferCopy = R"(#version 450 core
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D source;
layout(binding = 0, rgba16f) uniform writeonly image2DArray levels;
uniform int size;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(size)))) return;
  imageStore(levels, ivec3(p, 0), texelFetch(source, p, 0));
}
)";

// One invocation per row (or column): a running sum along it.
const char* const kSatPass = R"(#version 450 core
layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler2D input_tex;
layout(binding = 0, FORMAT) uniform writeonly image2D output_image;
uniform int size;
uniform int along_x;  // 1: rows, 0: columns
void main() {
  int line = int(gl_GlobalInvocationID.x);
  if (line >= size) return;
  vec4 sum = vec4(0.0);
  for (int i = 0; i < size; ++i) {
    ivec2 p = along_x == 1 ? ivec2(i, line) : ivec2(line, i);
    sum += texelFetch(input_tex, p, 0);
    imageStore(output_image, p, sum);
  }
}
)";

int log2_exact(int size) {
  int k = 0;
  while ((1 << k) < size) ++k;
  if ((1 << k) != size)
    throw std::invalid_argument("occlusion texture size must be a power of two");
  return k;
}

// The source's mip chain is sampled with trilinear filtering (a chain of one
// level, texel by texel, as the other textures are: the makers' nearest
// filtering and clamped edges).
gl::Texture make_mip_chain(GLenum format, int size, int levels) {
  gl::Texture t = gl::make_mipmapped_texture_2d(format, size, size, levels);
  if (levels > 1) {
    glTextureParameteri(t.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(t.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  }
  return t;
}

GLuint groups(int size) { return GLuint((size + kGroup - 1) / kGroup); }

}  // namespace

FilterPyramid::FilterPyramid(Filter filter, int size, bool sat_half)
    : filter_(filter), size_(size), levels_(log2_exact(size) + 1) {
  source_ = make_mip_chain(GL_RGBA8, size, levels_);
  if (filter == Filter::NBuffers) {
    nbuffers_ = gl::make_texture_2d_array(GL_RGBA16F, size, size, levels_);
    nbuffer_program_ = gl::Program::compute("nbuffer_level", kNBufferLevel);
    nbuffer_copy_program_ = gl::Program::compute("nbuffer_copy", kNBufferCopy);
  } else if (filter == Filter::Sat) {
    const GLenum format = sat_half ? GL_RGBA16F : GL_RGBA32F;
    const std::string image_format = sat_half ? "rgba16f" : "rgba32f";
    std::string pass = kSatPass;
    pass.replace(pass.find("FORMAT"), 6, image_format);
    sat_rows_ = gl::make_texture_2d(format, size, size);
    sat_ = gl::make_texture_2d(format, size, size);
    sat_rows_program_ = gl::Program::compute("sat_rows", pass);
    sat_columns_program_ = gl::Program::compute("sat_columns", pass);
    sat_format_ = format;
  }
  gl::throw_if_errors("occlusion filter pyramid");
}

void FilterPyramid::build() {
  switch (filter_) {
    case Filter::Mipmap:
      glGenerateTextureMipmap(source_.get());
      return;
    case Filter::NBuffers: {
      nbuffer_copy_program_.use();
      nbuffer_copy_program_.set("size", size_);
      glBindTextureUnit(0, source_.get());
      glBindImageTexture(0, nbuffers_.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
      glDispatchCompute(groups(size_), groups(size_), 1);
      nbuffer_program_.use();
      nbuffer_program_.set("size", size_);
      glBindTextureUnit(0, nbuffers_.get());
      for (int k = 1; k < levels_; ++k) {
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        nbuffer_program_.set("layer", k);
        nbuffer_program_.set("half_side", 1 << (k - 1));
        glDispatchCompute(groups(size_), groups(size_), 1);
      }
      glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
      return;
    }
    case Filter::Sat: {
      const auto lines = GLuint((size_ + 63) / 64);
      sat_rows_program_.use();
      sat_rows_program_.set("size", size_);
      sat_rows_program_.set("along_x", 1);
      glBindTextureUnit(0, source_.get());
      glBindImageTexture(0, sat_rows_.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, sat_format_);
      glDispatchCompute(lines, 1, 1);
      glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
      sat_columns_program_.use();
      sat_columns_program_.set("size", size_);
      sat_columns_program_.set("along_x", 0);
      glBindTextureUnit(0, sat_rows_.get());
      glBindImageTexture(0, sat_.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, sat_format_);
      glDispatchCompute(lines, 1, 1);
      glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
      return;
    }
  }
}

GLuint FilterPyramid::filtered() const {
  switch (filter_) {
    case Filter::Mipmap:
      return source_.get();
    case Filter::NBuffers:
      return nbuffers_.get();
    case Filter::Sat:
      return sat_.get();
  }
  return 0;
}

}  // namespace sb::techniques::occlusion_texture

namespace sb::techniques::occlusion_texture {
namespace {

const char* const kMipmapBoxMean = R"(
layout(binding = 4) uniform sampler2D pyramid[TEXTURES];
vec4 box_mean(int t, vec2 lo, vec2 hi) {
  vec2 side = hi - lo;
  float lod = 0.5 * log2(max(side.x * side.y, 1e-12));
  return textureLod(pyramid[t], 0.5 * (lo + hi) / float(size), max(lod, 0.0));
}
vec4 source_texel(int t, ivec2 p) { return texelFetch(pyramid[t], p, 0); }
)";

const char* const kNBuffersBoxMean = R"(
layout(binding = 4) uniform sampler2DArray pyramid[TEXTURES];
vec4 box_mean(int t, vec2 lo, vec2 hi) {
  ivec2 i0 = clamp(ivec2(round(lo)), ivec2(0), ivec2(size - 1));
  ivec2 i1 = clamp(ivec2(round(hi)), i0 + 1, ivec2(size));
  ivec2 side = i1 - i0;
  int level = findMSB(min(side.x, side.y));  // 2^level <= the shorter side
  int b = 1 << level;
  return 0.25 * (texelFetch(pyramid[t], ivec3(i0, level), 0) +
                 texelFetch(pyramid[t], ivec3(i1.x - b, i0.y, level), 0) +
                 texelFetch(pyramid[t], ivec3(i0.x, i1.y - b, level), 0) +
                 texelFetch(pyramid[t], ivec3(i1 - b, level), 0));
}
vec4 source_texel(int t, ivec2 p) { return texelFetch(pyramid[t], ivec3(p, 0), 0); }
)";

// F(x, y): the sum of the texels in [0, x) × [0, y), x and y integers in
// [0, size]; the table holds F(x + 1, y + 1) at texel (x, y).
const char* const kSatBoxMean = R"(
layout(binding = 4) uniform sampler2D pyramid[TEXTURES];
vec4 sat_sum(int t, int x, int y) {
  if (x <= 0 || y <= 0) return vec4(0.0);
  return texelFetch(pyramid[t], ivec2(min(x, size), min(y, size)) - 1, 0);
}
// The integral over [lo.x, hi.x] × [0, y) (continuous x, whole rows): each
// difference spans whole texels and is exact before the fractions weigh it.
vec4 sat_strip(int t, int x0, int x1, float f0, float f1, int y) {
  vec4 a0 = sat_sum(t, x0, y), a1 = sat_sum(t, x0 + 1, y);
  vec4 b0 = sat_sum(t, x1, y), b1 = sat_sum(t, x1 + 1, y);
  return (b0 - a0) + f1 * (b1 - b0) - f0 * (a1 - a0);
}
vec4 box_mean(int t, vec2 lo, vec2 hi) {
  ivec2 i0 = ivec2(floor(lo)), i1 = ivec2(floor(hi));
  vec2 f0 = lo - vec2(i0), f1 = hi - vec2(i1);
  vec4 s0 = sat_strip(t, i0.x, i1.x, f0.x, f1.x, i0.y);
  vec4 s1 = sat_strip(t, i0.x, i1.x, f0.x, f1.x, i0.y + 1);
  vec4 s2 = sat_strip(t, i0.x, i1.x, f0.x, f1.x, i1.y);
  vec4 s3 = sat_strip(t, i0.x, i1.x, f0.x, f1.x, i1.y + 1);
  vec4 integral = (s2 - s0) + f1.y * (s3 - s2) - f0.y * (s1 - s0);
  return integral / ((hi.x - lo.x) * (hi.y - lo.y));
}
vec4 source_texel(int t, ivec2 p) {
  return sat_sum(t, p.x + 1, p.y + 1) - sat_sum(t, p.x, p.y + 1) - sat_sum(t, p.x + 1, p.y) +
         sat_sum(t, p.x, p.y);
}
)";

}  // namespace

Filter filter_from_string(const std::string& s) {
  if (s == "mipmap") return Filter::Mipmap;
  if (s == "nbuffers") return Filter::NBuffers;
  if (s == "sat") return Filter::Sat;
  throw std::logic_error("unknown occlusion filter '" + s + "'");
}

std::string box_mean_glsl(Filter filter) {
  switch (filter) {
    case Filter::Mipmap:
      return kMipmapBoxMean;
    case Filter::NBuffers:
      return kNBuffersBoxMean;
    case Filter::Sat:
      return kSatBoxMean;
  }
  return "";
}

}  // namespace sb::techniques::occlusion_texture
