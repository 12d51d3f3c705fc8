#pragma once
// The full-screen pass every depth-map technique ends with: for each G-buffer
// pixel, find it in the light's map and write visibility
//   V = weight * above_horizon * lit_fraction(t)
// where `lit_fraction` is the variant's GLSL (one compare, k×k PCF, ...), `t`
// the pixel's light-space texture coordinates, and background pixels get
// V = weight. `weight` < 1 lets accumulation techniques add passes up.
#include <string>

#include "common/depth_pass.h"
#include "core/technique.h"
#include "gl/program.h"

namespace sb::shadow {

class MapLookupPass {
 public:
  MapLookupPass() = default;
  // `lit_fraction_glsl` defines `float lit_fraction(vec3 t)`; it may use
  // `shadow_map` (sampler2DShadow, unit 1) and its own uniforms.
  MapLookupPass(const std::string& name, const std::string& lit_fraction_glsl);

  const gl::Program& program() const { return program_; }
  // Draws into in.visibility_framebuffer (blending is the caller's choice).
  void draw(const FrameInputs& in, const LightFrustum& frustum, const DepthMapSettings& settings,
            GLuint shadow_map, float weight = 1.0f) const;

 private:
  gl::Program program_;
};

// A technique made of one depth map from the light's centre and one lookup:
// shadow_map, pcf and their kin differ only in `lit_fraction` and uniforms.
class SingleMapTechnique : public Technique {
 public:
  SingleMapTechnique(const Params& p, std::string name, std::string lit_fraction_glsl,
                     bool linear_filtering);
  void prepare(const FrameInputs& in) override;
  void render(const FrameInputs& in, gl::PassTimer& timer) override;

 protected:
  // Sets the variant's own uniforms on the lookup program, once, in prepare().
  virtual void set_uniforms(const gl::Program& /*lookup*/) const {}
  const DepthMapSettings& settings() const { return settings_; }

 private:
  std::string name_;
  std::string lit_fraction_glsl_;
  bool linear_filtering_;
  DepthMapSettings settings_;
  DepthMap map_;
  LightFrustum frustum_;
  MapLookupPass lookup_;
};

}  // namespace sb::shadow
