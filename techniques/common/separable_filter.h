#pragma once
// A separable k-tap prefilter over every layer of a 2D array texture: a
// horizontal pass into a scratch array, then a vertical pass back. Edges
// clamp. Used by the filterable shadow maps (VSM, ESM, EVSM, MSM, CSM).
//
// LogSumExp mode filters values v that stand for exp(c·v) without ever
// forming exp(c·v): out = m + log(Σ w_i·exp(c·(v_i − m)))/c, m the largest
// tap, so every exponent is <= 0 and fp32 cannot overflow at any c (the
// log-space filtering of exponential shadow maps, Salvi 2008).
//
// What the kit guarantees here (shadowbench::shadow_kit, installed):
//   in     a size×size×layers GL_TEXTURE_2D_ARRAY and k weights (odd k,
//          summing to 1; kernel.h makes them);
//   out    the same texture, each layer convolved with the weights along x
//          and then y, taps at whole texels, edges clamped;
//   GL     the constructor makes a scratch array of the same size and format,
//          framebuffers and a program: call it in prepare(). apply() turns
//          GL_DEPTH_TEST and GL_BLEND off, sets the viewport to size×size,
//          leaves its program in use, the last layer's framebuffer bound and
//          a texture on unit 0;
//   cost   2 × layers full-screen passes of size² texels × k taps; memory
//          the scratch array, as large as the target.
#include <vector>

#include "gl/objects.h"
#include "gl/program.h"

namespace sb::techniques {

// The separable prefilter above, over every layer of one array texture, in
// place: make it in prepare(), apply() it in every frame.
// units: taps one texel apart.
// cost: apply(): 2 × layers full-screen passes of size² texels × k taps;
// memory a scratch array as large as the target.
class SeparableFilter {
 public:
  enum class Mode { Linear, LogSumExp };

  SeparableFilter() = default;
  // `target`: a GL_TEXTURE_2D_ARRAY of size×size×layers in `internal_format`,
  // filtered in place. `weights`: odd count, summing to 1.
  SeparableFilter(GLuint target, GLenum internal_format, int size, int layers,
                  std::vector<float> weights, Mode mode, float exponent);
  void apply() const;
  int taps() const { return int(weights_.size()); }

 private:
  int size_ = 0;
  int layers_ = 0;
  std::vector<float> weights_;
  GLuint target_ = 0;
  gl::Texture scratch_;
  std::vector<gl::Framebuffer> target_layers_;
  std::vector<gl::Framebuffer> scratch_layers_;
  gl::Program program_;
};

// A size×size×layers array texture (nearest, clamped) and one framebuffer
// per layer drawing into it.
gl::Texture make_array_texture(GLenum internal_format, int size, int layers);
std::vector<gl::Framebuffer> layer_framebuffers(GLuint array_texture, int layers);

}  // namespace sb::techniques
