#include "occlusion_texture/filter_pyramid.h"

#include <stdexcept>
#include <string>

#include "gl/debug.h"

namespace sb::occlusion {
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

gl::Texture make_texture(GLenum target, int levels, GLenum format, int size, int layers) {
  GLuint id = 0;
  glCreateTextures(target, 1, &id);
  if (target == GL_TEXTURE_2D_ARRAY)
    glTextureStorage3D(id, levels, format, size, size, layers);
  else
    glTextureStorage2D(id, levels, format, size, size);
  glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, levels > 1 ? GL_LINEAR : GL_NEAREST);
  return gl::Texture(id);
}

GLuint groups(int size) { return GLuint((size + kGroup - 1) / kGroup); }

}  // namespace

FilterPyramid::FilterPyramid(Filter filter, int size, bool sat_half)
    : filter_(filter), size_(size), levels_(log2_exact(size) + 1) {
  source_ = make_texture(GL_TEXTURE_2D, levels_, GL_RGBA8, size, 1);
  if (filter == Filter::NBuffers) {
    nbuffers_ = make_texture(GL_TEXTURE_2D_ARRAY, 1, GL_RGBA16F, size, levels_);
    nbuffer_program_ = gl::Program::compute("nbuffer_level", kNBufferLevel);
    nbuffer_copy_program_ = gl::Program::compute("nbuffer_copy", kNBufferCopy);
  } else if (filter == Filter::Sat) {
    const GLenum format = sat_half ? GL_RGBA16F : GL_RGBA32F;
    const std::string image_format = sat_half ? "rgba16f" : "rgba32f";
    std::string pass = kSatPass;
    pass.replace(pass.find("FORMAT"), 6, image_format);
    sat_rows_ = make_texture(GL_TEXTURE_2D, 1, format, size, 1);
    sat_ = make_texture(GL_TEXTURE_2D, 1, format, size, 1);
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

}  // namespace sb::occlusion
