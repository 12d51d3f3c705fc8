#include "gl/storage_bytes.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "core/error.h"

namespace sb::gl {

using core::JobError;

namespace {

// Bits per texel of the sized internal formats of OpenGL 4.5 (tables 8.12
// and 8.13) that a texture or renderbuffer can have immutable storage of.
int bits_per_texel(GLenum f) {
  switch (f) {
    case GL_R8:
    case GL_R8_SNORM:
    case GL_R8I:
    case GL_R8UI:
    case GL_R3_G3_B2:
    case GL_STENCIL_INDEX8:
    case GL_RGBA2:
      return 8;
    case GL_RGB4:
      return 12;
    case GL_R16:
    case GL_R16_SNORM:
    case GL_R16F:
    case GL_R16I:
    case GL_R16UI:
    case GL_RG8:
    case GL_RG8_SNORM:
    case GL_RG8I:
    case GL_RG8UI:
    case GL_RGB5:
    case GL_RGB565:
    case GL_RGBA4:
    case GL_RGB5_A1:
    case GL_DEPTH_COMPONENT16:
      return 16;
    case GL_RGB8:
    case GL_RGB8_SNORM:
    case GL_RGB8I:
    case GL_RGB8UI:
    case GL_SRGB8:
    case GL_DEPTH_COMPONENT24:
      return 24;
    case GL_RGB10:
      return 30;
    case GL_RGB12:
      return 36;
    case GL_R32F:
    case GL_R32I:
    case GL_R32UI:
    case GL_RG16:
    case GL_RG16_SNORM:
    case GL_RG16F:
    case GL_RG16I:
    case GL_RG16UI:
    case GL_RGBA8:
    case GL_RGBA8_SNORM:
    case GL_RGBA8I:
    case GL_RGBA8UI:
    case GL_SRGB8_ALPHA8:
    case GL_RGB10_A2:
    case GL_RGB10_A2UI:
    case GL_R11F_G11F_B10F:
    case GL_RGB9_E5:
    case GL_DEPTH_COMPONENT32:
    case GL_DEPTH_COMPONENT32F:
    case GL_DEPTH24_STENCIL8:
      return 32;
    case GL_DEPTH32F_STENCIL8:
      return 40;
    case GL_RGBA12:
    case GL_RGB16:
    case GL_RGB16_SNORM:
    case GL_RGB16F:
    case GL_RGB16I:
    case GL_RGB16UI:
      return 48;
    case GL_RG32F:
    case GL_RG32I:
    case GL_RG32UI:
    case GL_RGBA16:
    case GL_RGBA16_SNORM:
    case GL_RGBA16F:
    case GL_RGBA16I:
    case GL_RGBA16UI:
      return 64;
    case GL_RGB32F:
    case GL_RGB32I:
    case GL_RGB32UI:
      return 96;
    case GL_RGBA32F:
    case GL_RGBA32I:
    case GL_RGBA32UI:
      return 128;
    default:
      return 0;
  }
}

}  // namespace

std::int64_t bytes_per_texel(GLenum internal_format) {
  const int bits = bits_per_texel(internal_format);
  if (bits == 0) {
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%04X", internal_format);
    throw JobError(std::string("GL internal format ") + hex +
                   " has no known size per texel (sized, uncompressed formats only)");
  }
  // The few formats of a fractional byte count (GL_RGB4, GL_RGB10, ...) are
  // rounded up to whole bytes, as no texel is stored in less.
  return (bits + 7) / 8;
}

std::int64_t texture_storage_bytes(GLenum internal_format, const TextureExtent& e) {
  const std::int64_t texel = bytes_per_texel(internal_format);
  std::int64_t texels = 0;
  for (int level = 0; level < e.levels; ++level) {
    const std::int64_t w = std::max(1, e.width >> level);
    const std::int64_t h = std::max(1, e.height >> level);
    const std::int64_t d = e.depth_halves ? std::max(1, e.depth >> level) : e.depth;
    texels += w * h * d;
  }
  return texels * texel * std::max(1, e.samples);
}

}  // namespace sb::gl
