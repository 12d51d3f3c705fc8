#pragma once
// The map pass of extended light maps (Brabec & Seidel 2000; Rahman 2007
// §2.5): the scene seen from the light's centre, writing beside the shadow
// information a "light channel" the final image's lighting would read, so
// that one pass over the scene does the work of two.
//
// - Shadow channel: either the depth buffer itself (24-bit normalised or
//   32-bit float, compared as shadow_map does), or the distance along the
//   light's axis, linear over the frustum's depth range, in the 8-bit alpha
//   channel, as the hardware of the time required (compared after
//   quantising the receiver's own distance the same way).
// - Light channel: rgb = the irradiance the light's centre gives the surface
//   the texel sees, cos θ · (n / r)², with θ the angle between the surface's
//   normal and the direction to the light, r the distance to it, n the
//   frustum's near distance (so that the value stays in [0, 1] for RGBA8).
//
// The light channel is written in the same pass as the shadow channel, in a
// second pass over the scene (what the single pass saves), or not at all.
// Alpha-tested meshes are drawn through their mask in every pass, as the
// shadow-map kit's depth pass draws them (common/depth_pass.h).
// Both ways write the same texels (tests/techniques/
// test_extended_light_map.cpp). The harness shades every technique alike,
// so nothing reads the light channel back: it is the published system's
// work, timed.
#include "common/depth_pass.h"
#include "gl/gpu_scene.h"
#include "gl/objects.h"
#include "gl/program.h"

namespace sb::techniques::shadow_map {

enum class ShadowChannel { Alpha8, Depth24, Depth32f };
enum class LightChannel { None, SamePass, SeparatePass };

struct ExtendedLightMapSettings {
  int size = 1024;
  ShadowChannel shadow = ShadowChannel::Alpha8;
  LightChannel light = LightChannel::SamePass;
  DepthBias bias;  // polygon offset in every pass
  CullMode cull = CullMode::Front;
};

class ExtendedLightMap {
 public:
  ExtendedLightMap() = default;
  explicit ExtendedLightMap(const ExtendedLightMapSettings& s);
  // The shadow channel (and the light channel with SamePass).
  void render_shadow_channel(const gl::GpuScene& gpu, const LightFrustum& f);
  // The light channel alone, over the depths the shadow channel left
  // (SeparatePass).
  void render_light_channel(const gl::GpuScene& gpu, const LightFrustum& f);
  GLuint color() const { return color_.get(); }  // RGBA8: rgb light, a 8-bit depth
  GLuint depth() const { return depth_.get(); }
  const ExtendedLightMapSettings& settings() const { return settings_; }

  // One pass's programs: for opaque meshes, and for alpha-tested ones (a
  // fragment shader that discards the mask's holes).
  struct Programs {
    gl::Program opaque;
    gl::Program masked;
  };

 private:
  void draw(const gl::GpuScene& gpu, const LightFrustum& f, const Programs& programs,
            bool writes_depth);

  ExtendedLightMapSettings settings_;
  gl::Texture color_, depth_;
  gl::Framebuffer framebuffer_;
  Programs both_, shadow_only_, light_only_, depth_only_;
};

// GLSL for a lookup: `light_map` (RGBA8, unit 4) and
// `float alpha8_lit(vec3 t, float bias_steps)`, the 8-bit comparison.
extern const char* const kAlpha8LookupGlsl;

}  // namespace sb::techniques::shadow_map
