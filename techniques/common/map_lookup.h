#pragma once
// The full-screen pass every depth-map technique ends with: for each G-buffer
// pixel, find it in the light's map and write visibility
//   V = weight * above_horizon * lit_fraction(t)
// where `lit_fraction` is the variant's GLSL (one compare, k×k PCF, a moment
// reconstruction...), `t` the pixel's light-space texture coordinates, and
// background pixels get V = weight. `weight` < 1 lets accumulation techniques
// add passes up. lit_fraction must itself return a value in [0,1]: nothing
// here clamps, so that NaN or overflow reach the harness's finiteness check.
//
// What `lit_fraction` may use besides `t` is the GLSL of
// common/map_lookup_glsl.h, which the pass puts before it: the samplers
// shadow_map (unit 1, comparisons) and depth_map (unit 3, raw window
// depths), the receiver (receiver_world, receiver_normal), shadow_tap(),
// view_depth(), receiver_view_depth(), depth01(), clamp_unit() and more.
// Units 4 and up are the variant's own. The pass prepends `#version 450 core`
// and that GLSL; lit_fraction_glsl must not have a #version of its own, nor
// redeclare what it declares.
//
// What the kit guarantees here (shadowbench::shadow_kit, installed):
//   in     the G-buffer and visibility target of FrameInputs, the frustum the
//          map was drawn with, the DepthMapSettings (normal offset, receiver
//          plane) and the map (DepthMap::texture());
//   out    V in every pixel of in.visibility_framebuffer, by the rule above:
//          0 where the map's eye (frustum.eye) is below the surface's
//          tangent plane (under an orthographic map, the sun: where the
//          sun's direction is),
//          `weight` outside the map's cone and on the background;
//   GL     MapLookupPass() compiles a program and makes two samplers: call it
//          in prepare(). draw() leaves in.visibility_framebuffer bound, the
//          viewport at in.width×in.height, GL_DEPTH_TEST off, its program in
//          use and textures on units 0-3 (samplers on 1 and 3 unbound
//          again); blending is left as the caller set it;
//   cost   one full-screen triangle: per pixel two G-buffer fetches and the
//          taps lit_fraction() makes.
//
// SingleMapTechnique times its passes as "shadow_map" (fit + depth pass) and
// "lookup", like every built-in map technique.
#include <string>

#include "common/depth_pass.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "plugin/technique.h"

namespace sb::techniques {

// The full-screen lookup pass (the rule at the top of this header): made
// from a variant's lit_fraction() GLSL in prepare(), drawn in every frame.
// cost: one full-screen triangle: per pixel two G-buffer fetches, the
// receiver's projection into the map and the taps lit_fraction() makes.
class MapLookupPass {
 public:
  MapLookupPass() = default;
  // `linear_compare`: shadow_map comparisons are bilinear (hardware 2×2 PCF).
  // `kit_glsl`: kit pieces lit_fraction calls (kPcfGlsl, kPcssGlsl, ...),
  // put before it, so that a compile error in lit_fraction_glsl names its
  // own line ("1:12(3): error"), as if the pieces were included.
  MapLookupPass(const std::string& name, const std::string& lit_fraction_glsl,
                bool linear_compare = false, const std::string& kit_glsl = {});

  const gl::Program& program() const { return program_; }
  // Draws into in.visibility_framebuffer (blending is the caller's choice).
  void draw(const plugin::FrameInputs& in, const LightFrustum& frustum,
            const DepthMapSettings& settings, GLuint depth_map, float weight = 1.0f) const;

 private:
  gl::Program program_;
  gl::Sampler compare_sampler_;
  gl::Sampler raw_sampler_;
};

// A technique made of one depth map from the light's centre (under the sun,
// one orthographic map along it: fit_single_map_frustum) and one lookup:
// shadow_map, the PCF kernels, PCSS and their kin differ only in
// `lit_fraction` and its uniforms. The light frustum is fitted in every
// frame (plugin/technique.h: prepare() must not depend on the light).
// Timed as "shadow_map" (fit + depth pass) and "lookup".
// cost: per frame the frustum fit (one matrix-vector product per caster
// index), the depth pass (DepthMap) and the lookup (MapLookupPass); memory
// the depth map.
class SingleMapTechnique : public plugin::Technique {
 public:
  // `kit_glsl` as MapLookupPass takes it: the kit pieces lit_fraction calls.
  SingleMapTechnique(const core::Params& p, std::string name, std::string lit_fraction_glsl,
                     bool linear_compare, std::string kit_glsl = {});
  void prepare(const plugin::FrameInputs& in) override;
  void render(const plugin::FrameInputs& in, gl::PassTimer& timer) override;

 protected:
  // The variant's own uniforms that depend on its parameters only: set once,
  // in prepare().
  virtual void set_uniforms(const gl::Program& /*lookup*/) const {}
  // Those that depend on the light or its frustum: set in every frame.
  virtual void set_light_uniforms(const gl::Program& /*lookup*/, const LightFrustum& /*frustum*/,
                                  const core::Scene& /*scene*/) const {}
  // The map's projection, fitted in every frame (timed, in the map's pass):
  // the casters seen from the light's centre, or a view-dependent warp.
  virtual LightFrustum fit(const plugin::FrameInputs& in) const;
  const DepthMapSettings& settings() const { return settings_; }

 private:
  std::string name_;
  std::string lit_fraction_glsl_;
  bool linear_compare_;
  std::string kit_glsl_;
  DepthMapSettings settings_;
  DepthMap map_;
  MapLookupPass lookup_;
};

}  // namespace sb::techniques
