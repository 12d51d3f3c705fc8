#pragma once
// A spatiotemporal denoiser for a stochastic technique's V (a few shadow
// rays per pixel, fresh samples each frame), in the SVGF family (Schied et
// al. 2017, "Spatiotemporal Variance-Guided Filtering", HPG):
//   1. "temporal": the pixel's world position (G-buffer) projected with the
//      previous frame's view-projection (kept here: the camera may move);
//      the 2×2 history texels around it kept where the previous frame's
//      surface lies on this pixel's plane and faces its way (disocclusion
//      rejects them); history length per pixel; V and its first two moments
//      blended with α = max(1 / length, alpha). Rejection "clamp" (the
//      default) first clamps the history to the noisy input's local mean
//      ± clamp_gamma·σ (TAA's neighbourhood clamp, Salvi 2016; AMD
//      FidelityFX Denoiser's shadows) and restarts the history where the
//      clamp moved it by more than clamp_reset: a moving light changes no
//      depth or normal, so the paper's tests alone ("none") let old
//      shadows ghost;
//   2. "variance": per pixel, the variance of V's samples from the temporal
//      moments, or, with under 4 frames of history, from a 7×7 edge-stopped
//      window of them (scaled by 4 / length, as the paper);
//   3. "atrous": edge-stopping à-trous wavelet passes (Dammertz 2010; 5×5
//      B3 kernel, step 2^i), weights from the world-position plane distance,
//      the normals (pow(max(0, n·n'), sigma_normal)) and the V difference
//      scaled by sigma_variance·sqrt(3×3-blurred variance); the variance is
//      filtered with the squared weights. The first iteration's output is
//      the next frame's history (as the paper).
// Temporal off: the variance from the 7×7 window of this frame's samples,
// then the à-trous passes (no history, no "temporal" pass).
//
// What the kit guarantees here (shadowbench::shadow_kit, installed):
//   in     FrameInputs (G-buffer position and both normals, view_projection,
//          view) and this frame's noisy V, an R32F texture width×height;
//   out    the filtered V in every pixel of in.visibility_framebuffer (1 on
//          background), in [0, 1] when the input is;
//   state  frame k after prepare() is a function of the inputs of frames
//          1..k (a technique using it is TechniqueInfo::temporal); prepare()
//          forgets every history;
//   GL     prepare() makes the textures (counted in gpu_bytes), framebuffers
//          and programs; denoise() turns depth, stencil, blending, the
//          scissor and culling off, writes every colour channel, sets the
//          viewport to width×height, and leaves a program in use, textures
//          on units 0–7 and the visibility framebuffer bound;
//   cost   per frame, timed as "temporal" (with temporal), "variance" and
//          "atrous": full-screen passes fetching per pixel about
//          4·clamp_radius + 2 (the clamp's row sums) and 3 + 16 +
//          2·clamp_radius + 1 texels (temporal), 4 (3 × 49 on pixels with
//          under 4 frames of history, and on every pixel with temporal
//          off: variance), and 36 per à-trous iteration; memory per pixel
//          2 × 44 bytes of history and 16 of the clamp's sums (with
//          temporal), and 2 × 16 of à-trous guides.
#include <optional>
#include <string>
#include <vector>

#include "core/params.h"
#include "gl/objects.h"
#include "gl/pass_timer.h"
#include "gl/program.h"
#include "plugin/technique.h"

namespace sb::techniques {

// What rejects a reprojected history besides disocclusion: Clamp to this
// frame's neighbourhood, or None (the paper's SVGF).
enum class HistoryRejection { None, Clamp };
// "none" / "clamp"; throws std::invalid_argument on another name.
HistoryRejection history_rejection_from_string(const std::string& s);

// The denoiser's settings; the defaults are the paper's except the clamp.
// units: V for clamp_reset; σ of the local window for clamp_gamma; the
// view distance for reprojection_tolerance; pixels for clamp_radius.
struct DenoiserSettings {
  bool temporal = true;
  HistoryRejection rejection = HistoryRejection::Clamp;
  int atrous_iterations = 4;  // 0..6
  float alpha = 0.2f;         // the temporal blend's floor (colour and moments)
  int max_history = 32;       // history length cap, frames
  float clamp_gamma = 1.0f;   // the clamp's half-width in local σ
  int clamp_radius = 3;       // the clamp's window, (2r + 1)² pixels
  float clamp_reset = 0.1f;   // the clamp moving V further restarts the history
  // History kept where |n·(x_prev − x)| < this × the pixel's view distance.
  float reprojection_tolerance = 0.02f;
  float sigma_plane = 0.2f;     // plane distance over tap distance
  float sigma_normal = 128.0f;  // exponent of n·n'
  float sigma_variance = 4.0f;  // V difference over sqrt(variance)
};

// A technique's parameters for the denoiser: `denoiser` ("none" | "svgf",
// default `default_denoiser`), denoiser_temporal, denoiser_rejection,
// denoiser_iterations, denoiser_alpha, denoiser_clamp_gamma.
std::vector<core::ParamSpec> denoiser_params(const std::string& default_denoiser);
// Reads every parameter of denoiser_params(); nullopt when `denoiser` is "none".
std::optional<DenoiserSettings> denoiser_settings(const core::Params& p);

// The denoiser above: prepare() it in a technique's prepare(), denoise()
// in every frame after the noisy V is written.
// units: pixels; V in [0, 1].
// cost: denoise(): the passes in this header's opening comment; memory as said there.
class VisibilityDenoiser {
 public:
  // Throws std::invalid_argument on settings out of range.
  explicit VisibilityDenoiser(DenoiserSettings settings = {});
  // Untimed: textures (histories cleared), framebuffers, programs; forgets
  // the camera and every history.
  void prepare(int width, int height);
  // One frame: `noisy` is this frame's R32F estimate (width×height); writes
  // the filtered V into in.visibility_framebuffer, every pixel (background 1).
  // cost: the "temporal", "variance" and "atrous" passes, each in a timer scope.
  void denoise(const plugin::FrameInputs& in, GLuint noisy, gl::PassTimer& timer);
  const DenoiserSettings& settings() const { return settings_; }

 private:
  void temporal_pass(const plugin::FrameInputs& in, GLuint noisy, int current, int previous);
  void variance_pass(const plugin::FrameInputs& in, GLuint noisy, int current);
  void atrous_passes(const plugin::FrameInputs& in, int current);

  DenoiserSettings settings_;
  int width_ = 0;
  int height_ = 0;
  // Histories, ping-ponged by frame: (V accumulated, m1, m2, length),
  // the filtered V, the G-buffer's position and geometric normal.
  gl::Texture moments_[2];
  gl::Texture color_[2];
  gl::Texture position_[2];
  gl::Texture normal_[2];
  gl::Framebuffer temporal_fb_[2];
  gl::Framebuffer history_fb_[2];  // à-trous ping-pong + the filtered-V history
  // The clamp's window, summed along rows: (Σv, Σv², count).
  gl::Texture window_rows_;
  gl::Framebuffer window_rows_fb_;
  // À-trous ping-pong: the guide (V, variance, eye distance, normal).
  gl::Texture ping_;
  gl::Texture pong_;
  gl::Framebuffer ping_fb_;
  gl::Framebuffer pong_fb_;
  gl::Program window_program_;
  gl::Program temporal_program_;
  gl::Program variance_program_;
  gl::Program atrous_program_;
  gl::Program atrous_final_program_;
  glm::mat4 previous_view_projection_{1.0f};
  bool has_history_ = false;
  int parity_ = 0;
};

}  // namespace sb::techniques
