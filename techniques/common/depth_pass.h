#pragma once
// The depth-only pass from a light point, shared by every shadow-map family.
//
// What the kit guarantees here (shadowbench::shadow_kit, installed):
//   in     the scene on the GPU (FrameInputs::gpu), a LightFrustum
//          (common/light_frustum.h) and the settings the parameters of
//          depth_map_params() give: size in texels, depth format, bias in
//          glPolygonOffset units and factor, culling;
//   out    DepthMap::texture(): a size×size depth texture of window depths
//          in [0, 1] (1 where nothing was drawn), clamped to a border of 1,
//          with compare mode off (the sampler bound with it decides);
//   GL     DepthMap() makes a texture, a framebuffer and two programs: call
//          it in prepare(), with a context. render() leaves its framebuffer
//          bound, the viewport at size×size, GL_DEPTH_TEST on with GL_LESS
//          and the depth mask on, one of its programs in use and, after an
//          alpha-tested caster, that caster's texture on unit 0; it restores
//          the colour mask and turns polygon offset and face culling off;
//   cost   one depth clear and one draw per caster mesh (and per receiver
//          with `receivers_too`); memory about size² × 4 bytes (2 with "16").
//
// Culling: only casters the harness found closed (DrawInfo::cullable) are
// culled, and it looks only when some technique of the run declared
// need::kCasterClosedness. A technique that culls must declare it, or its
// map would depend on which techniques run beside it.
#include <string>
#include <vector>

#include "common/light_frustum.h"
#include "common/map_lookup_glsl.h"  // kLightLookupGlsl, kLightDepthGlsl
#include "core/params.h"
#include "gl/gpu_scene.h"
#include "gl/objects.h"
#include "gl/program.h"

namespace sb::techniques {

// Which faces of closed casters the depth pass culls (the `cull` parameter).
enum class CullMode { None, Back, Front };
// The `cull` parameter's value as a CullMode: "none" | "back" | "front".
CullMode cull_mode_from_string(const std::string& s);
// Face culling for one mesh of a pass from the light: only closed casters
// are culled (receivers, double-sided and open meshes keep every face).
void set_depth_pass_cull(CullMode cull, const gl::DrawInfo& d);

// The depth pass's polygon offset (the constant_bias and slope_bias parameters).
// units: glPolygonOffset's (units of the depth format's resolution; factor per depth slope).
struct DepthBias {
  float constant = 0.0f;  // glPolygonOffset units
  float slope = 0.0f;     // glPolygonOffset factor
};

// The parameters every depth-map technique shares, declared once.
struct DepthMapSettings {
  int size = 2048;
  GLenum depth_format = GL_DEPTH_COMPONENT32F;  // "32f" | "24" | "16"
  DepthBias bias;
  CullMode cull = CullMode::Front;
  float normal_offset = 0.0f;  // texels along the receiver's normal (Holbert 2011)
  // Compare each filter tap against the receiver's plane extended to the
  // tap (Isidoro 2006), not against the pixel's own depth.
  bool receiver_plane = false;
  // The lookup's uniform `normal_offset` for a frustum: world units per unit
  // distance, or world units for an orthographic one (its texels have one size).
  float normal_offset_per_distance(const LightFrustum& f) const {
    return normal_offset * (f.orthographic ? f.texel_world(size) : f.texel_per_distance(size));
  }
};
// The parameters every depth-map technique shares: size, depth_format,
// constant_bias, slope_bias, cull, normal_offset.
std::vector<core::ParamSpec> depth_map_params(int default_size,
                                              const std::string& default_cull = "front");
// For variants whose filter taps compare depths away from the pixel.
core::ParamSpec receiver_plane_param();
// Reads depth_map_params (and receiver_plane_bias when declared).
DepthMapSettings depth_map_settings(const core::Params& p);

// The depth-only pass from a light point into a size×size depth texture
// (window depths in [0,1], 1 where nothing was drawn): make it in prepare(),
// render() it in every frame.
// units: size in texels; depths are window depths of the frustum drawn with.
// cost: render(): one depth clear and one draw per caster mesh (and per map
// receiver with `receivers_too`); memory size² × 4 bytes (2 with "16").
class DepthMap {
 public:
  DepthMap() = default;
  // A square depth map in `depth_format`. How it is read (compared or raw,
  // nearest or linear) is up to the sampler object bound with it.
  DepthMap(int size, GLenum depth_format);
  // `receivers_too`: also draw the receivers that have nothing behind them
  // from the light (DrawInfo::in_receiver_maps: a ground under everything),
  // unculled. Filtered maps need them: their filters average the occluder
  // depth with what lies around it, and an empty texel reads as the far
  // plane, which would drag every average far behind the real receiver.
  // Only closed casters are culled (`cull`); open and double-sided ones
  // keep both faces.
  void render(const gl::GpuScene& gpu, const LightFrustum& f, CullMode cull, DepthBias bias,
              bool receivers_too = false);
  GLuint texture() const { return texture_.get(); }
  int size() const { return size_; }

 private:
  int size_ = 0;
  gl::Texture texture_;
  gl::Framebuffer framebuffer_;
  gl::Program program_;
  gl::Program masked_program_;
};

}  // namespace sb::techniques
