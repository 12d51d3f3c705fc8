#include "common/filtered_map.h"

#include "gl/debug.h"

namespace sb::techniques {

using core::choice_param;
using core::Params;
using core::ParamSpec;
using plugin::FrameInputs;

namespace {

const char* const kBasisHead = R"(#version 450 core
layout(binding = 0) uniform sampler2D depth_map;
uniform int layer;
out vec4 result;
)";

const char* const kBasisMain = R"(
void main() {
  float w = texelFetch(depth_map, ivec2(gl_FragCoord.xy), 0).r;
  result = basis(depth01(view_depth(w)), layer);
}
)";

const char* const kFilteredLookupHead = R"(
layout(binding = 4) uniform sampler2DArray moments;
float receiver_depth01() { return depth01(receiver_view_depth()); }
)";

GLenum basis_format(int channels_per_layer, bool half_float) {
  switch (channels_per_layer) {
    case 1:
      return half_float ? GL_R16F : GL_R32F;
    case 2:
      return half_float ? GL_RG16F : GL_RG32F;
    default:
      return half_float ? GL_RGBA16F : GL_RGBA32F;
  }
}

}  // namespace

std::vector<ParamSpec> filtered_map_params(int default_size,
                                           const std::vector<std::string>& formats,
                                           const std::string& default_cull) {
  auto params = depth_map_params(default_size, default_cull);
  params.push_back(choice_param("format", formats.front(), formats,
                                "storage of the filtered basis values: 16- or 32-bit float"));
  params.push_back(choice_param("prefilter", "none", {"none", "box", "gauss"},
                                "separable prefilter of the basis values before the lookup"));
  params.push_back(
      kernel_size_param(5, "prefilter kernel SIDE (odd), in texels: k taps per separable pass"));
  params.push_back(kernel_sigma_param());
  return params;
}

FilteredMapSettings filtered_map_settings(const Params& p) {
  FilteredMapSettings s;
  s.depth = depth_map_settings(p);
  s.half_float = p.get_string("format") == "16f";
  const std::string prefilter = p.get_string("prefilter");
  if (prefilter != "none") s.prefilter = kernel_shape_from_string(prefilter);
  s.k = p.get_int("k");
  s.sigma = p.get_float("sigma");
  return s;
}

FilteredMapTechnique::FilteredMapTechnique(const Params& p, std::string name, BasisShader shader)
    : name_(std::move(name)), shader_(std::move(shader)), settings_(filtered_map_settings(p)) {
  layers_ = (shader_.channels + 3) / 4;
}

void FilteredMapTechnique::prepare(const FrameInputs& /*in*/) {
  const int size = settings_.depth.size;
  map_ = DepthMap(size, settings_.depth.depth_format);
  const GLenum format = basis_format(layers_ > 1 ? 4 : shader_.channels, settings_.half_float);
  moments_ = make_array_texture(format, size, layers_);
  // The lookup filters bilinearly; the basis and filter passes use texelFetch.
  glTextureParameteri(moments_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(moments_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  moment_layers_ = layer_framebuffers(moments_.get(), layers_);
  basis_ = gl::Program(name_ + "_basis", {gl::kFullscreenVertexShader, "",
                                          std::string(kBasisHead) + kLightDepthGlsl +
                                              shader_.basis_glsl + kBasisMain});
  filter_.reset();
  if (settings_.prefilter && settings_.k > 1)
    filter_.emplace(moments_.get(), format, size, layers_,
                    kernel_weights(*settings_.prefilter, settings_.k, settings_.sigma),
                    shader_.filter_mode, shader_.filter_exponent);
  lookup_ = MapLookupPass(name_ + "_lookup", kFilteredLookupHead + shader_.lit_fraction_glsl);
  set_uniforms(basis_, lookup_.program());
  gl::throw_if_errors(name_ + " prepare");
}

void FilteredMapTechnique::render(const FrameInputs& in, gl::PassTimer& timer) {
  LightFrustum frustum;
  {
    auto pass = timer.scope("shadow_map");
    frustum = fit_single_map_frustum(*in.scene);
    map_.render(*in.gpu, frustum, settings_.depth.cull, settings_.depth.bias,
                shader_.receivers_in_map);
  }
  {
    auto pass = timer.scope("moments");
    glDisable(GL_DEPTH_TEST);
    glViewport(0, 0, settings_.depth.size, settings_.depth.size);
    basis_.use();
    basis_.set("light_depth_range", glm::vec2(frustum.near_plane, frustum.far_plane));
    basis_.set("light_orthographic", frustum.orthographic ? 1 : 0);
    glBindTextureUnit(0, map_.texture());
    for (int l = 0; l < layers_; ++l) {
      if (layers_ > 1) basis_.set("layer", l);
      glBindFramebuffer(GL_FRAMEBUFFER, moment_layers_[size_t(l)].get());
      gl::draw_fullscreen_triangle();
    }
  }
  if (filter_) {
    auto pass = timer.scope("prefilter");
    filter_->apply();
  }
  auto pass = timer.scope("lookup");
  glBindTextureUnit(4, moments_.get());
  lookup_.draw(in, frustum, settings_.depth, map_.texture());
}

}  // namespace sb::techniques
