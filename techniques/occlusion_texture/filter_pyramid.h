#pragma once
// The prefiltered forms of an occlusion texture (Eisemann & Décoret 2008,
// §4) that let one lookup return the box-filtered occlusion over a square
// kernel of any size:
//
//   mipmap    the texture's own mip chain (glGenerateMipmap): 2^k-aligned
//             boxes of side 2^k, trilinear between levels.
//   nbuffers  Décoret's N-buffers: level k holds, at every texel, the mean
//             over the 2^k × 2^k box that starts there (a texture array,
//             one layer per level, each at full resolution); level k is
//             built from level k − 1 with four reads.
//   sat       a summed-area table, S(x, y) = Σ_{i<=x, j<=y} source: any box's
//             sum from four reads (Crow 1984). 32-bit floats keep every sum
//             of binary texels exact up to 2^24 (a 4096² texture); 16-bit
//             floats lose integers above 2048, which a 64² box already
//             exceeds.
//
// Each is built on the GPU from an RGBA texture (four slices, as the paper
// packs them), with compute programs for nbuffers and sat.
#include <string>

#include "gl/objects.h"
#include "gl/program.h"

namespace sb::techniques::occlusion_texture {

enum class Filter { Mipmap, NBuffers, Sat };

Filter filter_from_string(const std::string& s);  // "mipmap" | "nbuffers" | "sat"

// The texture unit of pyramid 0's filtered form in lookups; pyramid t is at
// kFirstLookupUnit + t.
constexpr int kFirstLookupUnit = 4;

// GLSL that reads TEXTURES pyramids bound from kFirstLookupUnit on (it needs
// `#define TEXTURES n` and `uniform int size` before it):
//   vec4 box_mean(int t, vec2 lo, vec2 hi)  pyramid t's source averaged over
//                                           the box [lo, hi] of texel
//                                           coordinates, inside [0, size]²
//                                           and of positive area;
//   vec4 source_texel(int t, ivec2 p)       one texel of the source.
// mipmap: one trilinear lookup at the box's centre, at the level of its
// mean side. nbuffers: the four boxes of side 2^k (the box's shorter side
// rounded down to a power of two) at its corners, averaged. sat: the exact
// integral of the texels over the box, fractional edges included (bilinear
// between the table's entries), differenced before it is weighted so that
// 32-bit sums stay exact.
std::string box_mean_glsl(Filter filter);

class FilterPyramid {
 public:
  // `size`: the occlusion texture's side (a power of two). `sat_half`: the
  // SAT in 16-bit floats instead of 32 (to show what that loses).
  FilterPyramid(Filter filter, int size, bool sat_half = false);

  // The occlusion texture to render into: RGBA8, with a full mip chain
  // (levels beyond 0 are used by `mipmap` only).
  GLuint source() const { return source_.get(); }
  // Builds the filtered form from the source's level 0.
  void build();
  // Binds what box_mean_glsl reads to `unit`.
  void bind_for_lookup(GLuint unit) const { glBindTextureUnit(unit, filtered()); }
  // What lookups read: the source itself (mipmap), the N-buffer array
  // (RGBA16F, levels() layers), or the SAT (RGBA32F or RGBA16F).
  GLuint filtered() const;
  int levels() const { return levels_; }  // log2(size) + 1
  int size() const { return size_; }

 private:
  Filter filter_;
  int size_;
  int levels_;
  gl::Texture source_;
  gl::Texture nbuffers_;
  gl::Texture sat_rows_;  // the rows' prefix sums, before the columns'
  gl::Texture sat_;
  gl::Program nbuffer_copy_program_;
  gl::Program nbuffer_program_;
  gl::Program sat_rows_program_;
  gl::Program sat_columns_program_;
  GLenum sat_format_ = GL_RGBA32F;
};

}  // namespace sb::techniques::occlusion_texture
