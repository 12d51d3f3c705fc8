#pragma once
// The depth-only pass from a light point, shared by every shadow-map family.
#include <string>
#include <vector>

#include "common/light_frustum.h"
#include "core/params.h"
#include "gl/gpu_scene.h"
#include "gl/objects.h"
#include "gl/program.h"

namespace sb::shadow {

enum class CullMode { None, Back, Front };
CullMode cull_mode_from_string(const std::string& s);  // "none" | "back" | "front"

struct DepthBias {
  float constant = 0.0f;  // glPolygonOffset units
  float slope = 0.0f;     // glPolygonOffset factor
};

// The parameters every depth-map technique shares, declared once.
struct DepthMapSettings {
  int size = 2048;
  DepthBias bias;
  CullMode cull = CullMode::Front;
  float normal_offset = 0.0f;  // texels along the receiver's normal (Holbert 2011)
  // The lookup's uniform `normal_offset` for a frustum: world units per unit distance.
  float normal_offset_per_distance(const LightFrustum& f) const {
    return normal_offset * f.texel_per_distance(size);
  }
};
std::vector<ParamSpec> depth_map_params(
    int default_size);  // size, constant_bias, slope_bias, cull, normal_offset
DepthMapSettings depth_map_settings(const Params& p);

class DepthMap {
 public:
  DepthMap() = default;
  // A square GL_DEPTH_COMPONENT32F map; compare=true sets it up as a
  // sampler2DShadow (linear=true gives hardware 2×2 PCF).
  DepthMap(int size, bool compare, bool linear);
  void render(const GpuScene& gpu, const LightFrustum& f, CullMode cull, DepthBias bias);
  GLuint texture() const { return texture_.get(); }
  int size() const { return size_; }

 private:
  int size_ = 0;
  gl::Texture texture_;
  gl::Framebuffer framebuffer_;
  gl::Program program_;
  gl::Program masked_program_;
};

// GLSL helpers for lookup passes: `light_coords(world)` returns the point in
// the light's [0,1]^3 texture space, depth clamped to 1 so receivers beyond
// the far plane compare as unshadowed when nothing is in front of them;
// `offset_world(world, n, light_point, normal_offset)` moves the receiver
// along its normal by normal_offset × its distance to the light point;
// `above_horizon(n, world, light_point)` is 0 for light points below the
// surface's tangent plane (the surface occludes them itself).
extern const char* const kLightLookupGlsl;

}  // namespace sb::shadow
