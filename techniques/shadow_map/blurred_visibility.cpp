// blurred_visibility — the "common in games" soft shadow (Shypula 2008
// §5.2): the hard visibility of one shadow map from the light's centre,
// blurred by a separable Gaussian of a fixed radius, whatever the distance
// between occluder and receiver.
//
// space = "screen": the hard V image is blurred in the camera's image. Only
// geometry pixels are averaged (the weights of background pixels are left
// out and the rest renormalised), so the sky neither lights nor darkens the
// silhouettes of the scene against it; background stays V = 1.
//
// space = "light": the occluder mask of the map (1 where a caster covers the
// texel, 0 where the map is empty) is blurred in the map's texture space, the
// projected "shadow texture" of older engines, and looked up per pixel:
//   - a pixel the hard test shadows takes 1 − the blurred mask (its umbra
//     lightens towards the edge);
//   - a lit pixel whose own texel is covered is the caster's front surface,
//     nearest the light: V = 1 (the texture is not projected onto the
//     caster that made it);
//   - a lit pixel whose texel is empty is a receiver beyond every caster:
//     1 − the blurred mask (the outer half of the penumbra).
// The blur costs one pass over the map per direction, independent of the
// number of pixels on screen.
//
// The known failure, on purpose: the softness is the same at an occluder's
// foot, where the true shadow is hard, as at its far end
// (docs/survey_techniques.md measures it on the `standing` scene).
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "common/depth_pass.h"
#include "common/kernel.h"
#include "common/map_lookup.h"
#include "common/separable_filter.h"
#include "gl/debug.h"
#include "shadow_map/shadow_map_variants.h"

namespace sb::techniques::shadow_map {
namespace {

// The lookup of space = "light": unit 4 holds the blurred mask.
const char* const kLightSpaceLookup = R"(
layout(binding = 4) uniform sampler2DArray blurred_mask;
float lit_fraction(vec3 t) {
  bool lit = texture(shadow_map, t) > 0.5;
  bool covered = texture(depth_map, t.xy).r < 1.0;
  if (lit && covered) return 1.0;
  return 1.0 - clamp_unit(texture(blurred_mask, vec3(t.xy, 0.0)).r);
}
)";

// 1 where the map holds a caster, 0 where it is empty (cleared to far).
const char* const kMaskFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D depth_map;
out float mask;
void main() {
  mask = texelFetch(depth_map, ivec2(gl_FragCoord.xy), 0).r < 1.0 ? 1.0 : 0.0;
}
)";

// One direction of the screen-space blur over geometry pixels only.
const char* const kScreenBlurFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D source;
layout(binding = 1) uniform sampler2D position_tex;
uniform ivec2 direction;
uniform int radius;
uniform float weights[63];
out float visibility;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  if (texelFetch(position_tex, p, 0).w == 0.0) {
    visibility = 1.0;
    return;
  }
  ivec2 last = textureSize(source, 0) - 1;
  float sum = 0.0, weight = 0.0;
  for (int i = -radius; i <= radius; ++i) {
    ivec2 q = p + i * direction;
    if (any(lessThan(q, ivec2(0))) || any(greaterThan(q, last))) continue;
    if (texelFetch(position_tex, q, 0).w == 0.0) continue;
    float w = weights[i + radius];
    sum += w * texelFetch(source, q, 0).r;
    weight += w;
  }
  visibility = sum / weight;  // the centre is geometry: weight > 0
}
)";

enum class BlurSpace { Screen, Light };

class BlurredVisibility final : public Technique {
 public:
  explicit BlurredVisibility(const Params& p)
      : space_(p.get_string("space") == "light" ? BlurSpace::Light : BlurSpace::Screen),
        radius_(p.get_int("radius")),
        settings_(depth_map_settings(p)) {}

  void prepare(const FrameInputs& in) override {
    const int taps = 2 * radius_ + 1;
    // ±2σ within the radius: the kernel's tails hold 5% of its weight.
    weights_ = kernel_weights(KernelShape::Gauss, taps, 0.5f * float(radius_));
    map_ = DepthMap(settings_.size, settings_.depth_format);
    if (space_ == BlurSpace::Screen) {
      lookup_ = MapLookupPass("blurred_visibility_lookup",
                              "float lit_fraction(vec3 t) { return texture(shadow_map, t); }\n");
      screen_blur_ = gl::Program("blurred_visibility_screen_blur",
                                 {gl::kFullscreenVertexShader, "", kScreenBlurFragment});
      scratch_ = gl::make_texture_2d(GL_R32F, in.width, in.height);
      scratch_framebuffer_ = gl::make_framebuffer({scratch_.get()}, 0);
      set_weights(screen_blur_);
    } else {
      lookup_ = MapLookupPass("blurred_visibility_lookup", kLightSpaceLookup);
      mask_program_ =
          gl::Program("blurred_visibility_mask", {gl::kFullscreenVertexShader, "", kMaskFragment});
      mask_ = make_array_texture(GL_R32F, settings_.size, 1);
      // Outside the map nothing covers the light: the mask reads 0 there.
      glTextureParameteri(mask_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTextureParameteri(mask_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTextureParameteri(mask_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
      glTextureParameteri(mask_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
      mask_layers_ = layer_framebuffers(mask_.get(), 1);
      mask_filter_ = SeparableFilter(mask_.get(), GL_R32F, settings_.size, 1, weights_,
                                     SeparableFilter::Mode::Linear, 0.0f);
    }
    gl::throw_if_errors("blurred_visibility prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    LightFrustum frustum;
    {
      auto pass = timer.scope("shadow_map");
      frustum = fit_light_frustum(*in.scene, in.scene->light.center);
      map_.render(*in.gpu, frustum, settings_.cull, settings_.bias);
    }
    if (space_ == BlurSpace::Light) {
      {
        auto pass = timer.scope("mask");
        glBindFramebuffer(GL_FRAMEBUFFER, mask_layers_[0].get());
        glViewport(0, 0, settings_.size, settings_.size);
        glDisable(GL_DEPTH_TEST);
        mask_program_.use();
        glBindTextureUnit(0, map_.texture());
        gl::draw_fullscreen_triangle();
      }
      {
        auto pass = timer.scope("blur");
        mask_filter_.apply();
      }
      auto pass = timer.scope("lookup");
      glBindTextureUnit(4, mask_.get());
      lookup_.draw(in, frustum, settings_, map_.texture());
      return;
    }
    {
      auto pass = timer.scope("lookup");
      lookup_.draw(in, frustum, settings_, map_.texture());
    }
    auto pass = timer.scope("blur");
    glDisable(GL_DEPTH_TEST);
    screen_blur_.use();
    glBindTextureUnit(1, in.gbuffer_position);
    // Horizontal: visibility → scratch; vertical: scratch → visibility.
    glBindFramebuffer(GL_FRAMEBUFFER, scratch_framebuffer_.get());
    glViewport(0, 0, in.width, in.height);
    screen_blur_.set("direction", glm::ivec2(1, 0));
    glBindTextureUnit(0, in.visibility_texture);
    gl::draw_fullscreen_triangle();
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    screen_blur_.set("direction", glm::ivec2(0, 1));
    glBindTextureUnit(0, scratch_.get());
    gl::draw_fullscreen_triangle();
  }

 private:
  void set_weights(const gl::Program& program) const {
    program.set("radius", radius_);
    program.set("weights", weights_);
  }

  BlurSpace space_;
  int radius_;
  DepthMapSettings settings_;
  std::vector<float> weights_;
  DepthMap map_;
  MapLookupPass lookup_;
  gl::Program screen_blur_;
  gl::Texture scratch_;
  gl::Framebuffer scratch_framebuffer_;
  gl::Program mask_program_;
  gl::Texture mask_;
  std::vector<gl::Framebuffer> mask_layers_;
  SeparableFilter mask_filter_;
};

}  // namespace

TechniqueInfo blurred_visibility_info() {
  std::vector<ParamSpec> params = {
      choice_param("space", "screen", {"screen", "light"},
                   "where the hard visibility is blurred: the camera's image (geometry pixels "
                   "only) or the map's texture space (the occluder mask)"),
      int_param("radius", 4, 1, (kMaxKernelTaps - 1) / 2,
                "Gaussian radius in pixels (screen) or map texels (light); σ = radius / 2")};
  for (auto& p : depth_map_params(2048)) params.push_back(std::move(p));
  return {
      .name = "blurred_visibility",
      .family = "shadow_map",
      .summary =
          "the hard shadow map's visibility blurred by a fixed-radius Gaussian in screen or light "
          "space (Shypula 2008 §5.2)",
      .needs = Needs{need::kCasterClosedness},
      .params = std::move(params),
      .create = [](const Params& p) { return std::make_unique<BlurredVisibility>(p); }};
}

}  // namespace sb::techniques::shadow_map
