// penumbra_maps (Wyman & Hansen 2003) and smoothies (Chan & Durand 2003):
// a hard shadow map from the light's centre, plus a second light-space
// buffer drawn from the silhouette edges seen from that centre, which
// darkens the lit side of every hard edge: the OUTER penumbra only. The hard
// shadow stays the umbra, so both overestimate it by the inner half of the
// true penumbra; docs/survey_techniques.md measures that.
//
// The geometry: one band per silhouette edge (common/silhouette_band.h,
// drawn straight from the harness's edge buffer) on its outer side in the
// map's image plane, as wide as the widest penumbra the edge can cast. An
// occluder point at depth z_o casts the light's rectangle scaled by
// s = 1/z_o − 1/z_r onto a receiver at depth z_r (image-plane units; 1/z is
// linear along the projected edge), so a fragment's darkness from the edge
// is 1 − min over the edge's points of g/s, g its light-shaped distance
// from the point (silhouette_band.h): the light's support function wide
// along the edge ("sheets"), its rectangle at the ends ("cones"), exact in
// extent for a straight edge parallel to the light.
//
// penumbra_maps: the map holds the receivers too (DepthMap receivers_too),
// so every texel knows the nearest surface z_r behind the band, and the
// penumbra buffer keeps, by MAX blending, the largest darkness over all
// bands: V = 0 where the hard test shadows, else 1 − that darkness. The map
// is biased (constant_bias, slope_bias) so that the receivers do not shadow
// themselves.
//
// smoothies: the bands are a fixed `width_texels` wide ("smoothies", whose
// width bounds the penumbra they can show), and the buffer keeps, by depth
// test, the band nearest the light with its g and z_o at the edge's point of
// least g·z_o (the ratio for a receiver at infinity). The lookup uses the
// pixel's own depth: V = min(1, g · z_o · z_r / (z_r − z_o)), Chan &
// Durand's α' = α · b / (r − b) up to the units.
//
// Alpha masks: both papers take the silhouette from the meshes' edges, and a
// mask's outline is no edge (every leaf quad's outline would cast a
// penumbra where the leaf has none), so both need opaque casters and are
// skipped on masked scenes (docs/design.md, "Alpha masks everywhere").
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <memory>
#include <string>
#include <vector>

#include "common/depth_pass.h"
#include "common/light_frame.h"
#include "common/map_lookup.h"
#include "common/silhouette_band.h"
#include "gl/debug.h"
#include "penumbra_map/outer_penumbra_variants.h"

namespace sb::techniques::penumbra_map {
namespace {

const char* const kBandVertex = R"(
uniform mat4 light_view;
uniform mat4 light_projection;
uniform vec3 light_center;
uniform vec2 light_depth_range;  // near, far
uniform vec2 light_hu;           // the light's half axes in the light view's x, y
uniform vec2 light_hv;
uniform bool fixed_width;        // smoothies
uniform float band_width;        // smoothies: image-plane units
flat out vec2 a_image, b_image;
flat out vec2 inverse_depths;    // 1 / z_o at a and b
flat out vec2 outward;           // image plane, away from the occluder
void main() {
  Edge e = edges[gl_VertexID / kBandVertices];
  if (!on_silhouette(e, light_center)) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // every vertex the same: no area
    return;
  }
  vec3 ea = (light_view * vec4(e.p0.xyz, 1.0)).xyz, eb = (light_view * vec4(e.p1.xyz, 1.0)).xyz;
  float za = -ea.z, zb = -eb.z;  // > 0: the frustum fit keeps casters in front of the light
  a_image = ea.xy / za;
  b_image = eb.xy / zb;
  inverse_depths = vec2(1.0 / za, 1.0 / zb);
  // The widest outer penumbra the edge casts: on the far plane, from its nearer end.
  float zo = min(za, zb), far = light_depth_range.y;
  float reach = (length(light_hu) + length(light_hv)) * max(far - zo, 0.0) / (zo * far);
  float r = fixed_width ? band_width : reach;
  // The occluder's side in the image plane: the derivative of xy / −z at the
  // edge's middle along the direction into its lit face. Only the other
  // side gets a band; the hard test owns the occluder's side.
  vec3 m = 0.5 * (ea + eb), into = mat3(light_view) * into_lit_face(e, light_center);
  vec2 inside = into.xy + (m.xy / -m.z) * into.z;
  outward = outward_normal(a_image, b_image, inside);
  vec2 corner = band_corner(a_image, b_image, r, outward, gl_VertexID % kBandVertices);
  float z = 0.5 * (light_depth_range.x + far);  // any depth: the image plane is what counts
  gl_Position = light_projection * vec4(corner * z, -z, 1.0);
}
)";

const char* const kBandFragmentHead = R"(
uniform mat4 light_projection;
uniform vec2 light_hu;
uniform vec2 light_hv;
uniform float band_width;
flat in vec2 a_image, b_image;
flat in vec2 inverse_depths;
flat in vec2 outward;
// The fragment in the map's image plane; fragments on the occluder's side
// of the edge's line are discarded.
vec2 band_image() {
  vec2 image = fragment_image();
  if (dot(image - a_image, outward) < 0.0) discard;
  return image;
}
)";

const char* const kPenumbraMapFragment = R"(
layout(binding = 1) uniform sampler2D depth_map;
out float darkness;
void main() {
  vec2 image = band_image();
  float w = texelFetch(depth_map, ivec2(gl_FragCoord.xy), 0).r;
  if (w >= 1.0) discard;  // nothing behind the band
  // The light's scale on the receiver, 1/z_o − 1/z_r, is linear along the edge.
  float inverse_zr = 1.0 / view_depth(w), t;
  float ratio = light_ratio(image, a_image, b_image, light_hu, light_hv,
                            inverse_depths.x - inverse_zr, inverse_depths.y - inverse_zr, t);
  darkness = clamp(1.0 - ratio, 0.0, 1.0);
}
)";

// The smoothie's point of the edge is the one with the least g · z_o (the
// ratio for a receiver at infinity); the lookup rescales its g to the
// receiver's depth.
const char* const kSmoothieFragment = R"(
out vec2 smoothie;  // g, z_o
void main() {
  vec2 image = band_image();
  float s = segment_param(image, a_image, b_image);
  if (length(image - mix(a_image, b_image, s)) > band_width) discard;
  float t;
  light_ratio(image, a_image, b_image, light_hu, light_hv, inverse_depths.x, inverse_depths.y, t);
  float zo = 1.0 / mix(inverse_depths.x, inverse_depths.y, t);
  smoothie = vec2(light_distance_at(image, a_image, b_image, light_hu, light_hv, t), zo);
  vec4 clip = light_projection * vec4(0.0, 0.0, -zo, 1.0);
  gl_FragDepth = 0.5 * clip.z / clip.w + 0.5;  // the nearest smoothie wins
}
)";

const char* const kPenumbraMapLookup = R"(
layout(binding = 4) uniform sampler2D penumbra;
float lit_fraction(vec3 t) {
  if (texture(shadow_map, t) < 0.5) return 0.0;
  return 1.0 - clamp_unit(texture(penumbra, t.xy).r);
}
)";

const char* const kSmoothieLookup = R"(
layout(binding = 4) uniform sampler2D smoothie;
float lit_fraction(vec3 t) {
  if (texture(shadow_map, t) < 0.5) return 0.0;
  vec2 s = texture(smoothie, t.xy).rg;  // 0: no smoothie
  float zr = receiver_view_depth(), zo = s.y;
  if (zo <= 0.0 || zr <= zo) return 1.0;
  return min(1.0, s.x * zo * zr / (zr - zo));  // g / the light's scale on the receiver
}
)";

enum class Kind { PenumbraMap, Smoothie };

class OuterPenumbra final : public Technique {
 public:
  OuterPenumbra(const Params& p, Kind kind)
      : kind_(kind),
        settings_(depth_map_settings(p)),
        width_texels_(kind == Kind::Smoothie ? p.get_float("width_texels") : 0.0f) {}

  void prepare(const FrameInputs& /*in*/) override {
    const bool smoothie = kind_ == Kind::Smoothie;
    const std::string name = smoothie ? "smoothies" : "penumbra_maps";
    map_ = DepthMap(settings_.size, settings_.depth_format);
    band_ = gl::Program(
        name + "_bands",
        {std::string("#version 450 core\n") + kSilhouetteBandVertexGlsl + kBandVertex, "",
         std::string("#version 450 core\n") + kLightDepthGlsl + kSilhouetteBandFragmentGlsl +
             kBandFragmentHead + (smoothie ? kSmoothieFragment : kPenumbraMapFragment)});
    buffer_ = gl::make_texture_2d(smoothie ? GL_RG32F : GL_R32F, settings_.size, settings_.size);
    // Outside the map no band was drawn: the border reads "none".
    glTextureParameteri(buffer_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
    glTextureParameteri(buffer_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
    if (smoothie) {
      band_depth_ = gl::make_depth_texture(GL_DEPTH_COMPONENT32F, settings_.size, settings_.size,
                                           /*compare=*/false);
    }
    framebuffer_ = gl::make_framebuffer({buffer_.get()}, band_depth_.get());
    lookup_ = MapLookupPass(name + "_lookup", smoothie ? kSmoothieLookup : kPenumbraMapLookup);
    gl::throw_if_errors(name + " prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    const bool smoothie = kind_ == Kind::Smoothie;
    LightFrustum frustum;
    {
      auto pass = timer.scope("shadow_map");
      frustum = fit_light_frustum(*in.scene, in.scene->light.center);
      map_.render(*in.gpu, frustum, settings_.cull, settings_.bias, /*receivers_too=*/!smoothie);
    }
    {
      auto pass = timer.scope(smoothie ? "smoothies" : "penumbra_map");
      glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
      glViewport(0, 0, settings_.size, settings_.size);
      const float none[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      glClearBufferfv(GL_COLOR, 0, none);
      glDisable(GL_CULL_FACE);
      if (smoothie) {
        const float far = 1.0f;
        glClearBufferfv(GL_DEPTH, 0, &far);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
      } else {
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        glBlendEquation(GL_MAX);
        glBlendFunc(GL_ONE, GL_ONE);
      }
      set_band_uniforms(in, frustum);
      glBindTextureUnit(1, map_.texture());
      // A light without area has no penumbra: the hard map alone.
      if (LightFrame(in.scene->light).has_area()) draw_silhouette_bands(in);
      glDisable(GL_BLEND);
      glBlendEquation(GL_FUNC_ADD);
      glDisable(GL_DEPTH_TEST);
    }
    auto pass = timer.scope("lookup");
    glBindTextureUnit(4, buffer_.get());
    lookup_.draw(in, frustum, settings_, map_.texture());
  }

 private:
  void set_band_uniforms(const FrameInputs& in, const LightFrustum& frustum) const {
    const AreaLight& light = in.scene->light;
    const glm::mat3 rotation(frustum.view);
    // Each variant's shaders leave some of these out.
    band_.use();
    band_.set_if_active("light_view", frustum.view);
    band_.set_if_active("light_projection", frustum.projection);
    band_.set_if_active("light_center", light.center);
    band_.set_if_active("light_depth_range", glm::vec2(frustum.near_plane, frustum.far_plane));
    band_.set_if_active("light_hu", glm::vec2(rotation * light.half_u));
    band_.set_if_active("light_hv", glm::vec2(rotation * light.half_v));
    band_.set_if_active("fixed_width", kind_ == Kind::Smoothie ? 1 : 0);
    set_fragment_image_uniforms(band_, frustum, settings_.size);
    // Smoothies: the width in texels, in the image plane's units.
    band_.set_if_active("band_width", width_texels_ * frustum.texel_per_distance(settings_.size));
  }

  Kind kind_;
  DepthMapSettings settings_;
  float width_texels_;
  DepthMap map_;
  gl::Program band_;
  gl::Texture buffer_;
  gl::Texture band_depth_;
  gl::Framebuffer framebuffer_;
  MapLookupPass lookup_;
};

}  // namespace

TechniqueInfo penumbra_maps_info() {
  return {.name = "penumbra_maps",
          .family = "penumbra_map",
          .summary =
              "a hard shadow map plus a penumbra map drawn from the light centre's silhouette "
              "edges (cones and sheets): the outer penumbra only (Wyman & Hansen 2003)",
          .needs = Needs{need::kRectangularLight, need::kOpaqueCasters, need::kCasterClosedness,
                         need::kSilhouetteEdges},
          .params = depth_map_params(1024),
          .create = [](const Params& p) {
            return std::make_unique<OuterPenumbra>(p, Kind::PenumbraMap);
          }};
}

TechniqueInfo smoothies_info() {
  std::vector<ParamSpec> params = {float_param(
      "width_texels", 32.0, 0.5, 4096.0,
      "the smoothies' fixed width in map texels: the widest outer penumbra they can show")};
  for (auto& p : depth_map_params(1024)) params.push_back(std::move(p));
  return {
      .name = "smoothies",
      .family = "penumbra_map",
      .summary =
          "a hard shadow map plus fixed-width smoothies on the light centre's silhouette edges, "
          "rescaled by the receiver's depth: the outer penumbra only (Chan & Durand 2003)",
      .needs = Needs{need::kRectangularLight, need::kOpaqueCasters, need::kCasterClosedness,
                     need::kSilhouetteEdges},
      .params = std::move(params),
      .create = [](const Params& p) { return std::make_unique<OuterPenumbra>(p, Kind::Smoothie); }};
}

}  // namespace sb::techniques::penumbra_map
