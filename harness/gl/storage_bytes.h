#pragma once
// The bytes of storage a technique asks the GL for, from the sized internal
// format's bits (docs/results.md, technique.gpu_bytes): what was requested,
// not what a driver pads it to (GL_DEPTH_COMPONENT24 is 3 bytes here, 4 on
// most GPUs), nor compression.
#include <cstdint>

#include "gl/gl.h"

namespace sb::gl {

// Bytes of one texel of a sized, uncompressed internal format. Throws
// JobError (core/error.h) for another format: a texture of it would have a
// size the record cannot state.
std::int64_t bytes_per_texel(GLenum internal_format);

// Storage of a texture of `levels` mip levels: each level's width and height
// (and depth, for a 3D texture: `depth_halves`) halve, down to 1; array
// layers keep their count at every level. `samples` multiplies (0 and 1: one).
struct TextureExtent {
  int width = 1, height = 1, depth = 1;  // depth: 3D depth or array layers
  int levels = 1;
  bool depth_halves = false;  // a 3D texture's depth, not an array's layers
  int samples = 1;
};
std::int64_t texture_storage_bytes(GLenum internal_format, const TextureExtent& extent);

}  // namespace sb::gl
