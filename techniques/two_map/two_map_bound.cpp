// two_map_bound — the two-shadow-map penumbra bound that Shypula 2008
// (ch. 8) proposes and, as far as we know, nobody built: two hard maps,
// from the apexes of the penumbra and umbra frusta that the light's
// rectangle and the casters' extent span (apex_placement.h,
// docs/survey_techniques.md draws them), classify every pixel:
//   lit       seen from both apexes                    V = 1
//   umbra     hidden from both                         V = 0
//   penumbra  hidden from one (the penumbra apex, or, inconsistently, only
//             the umbra apex)                          V from `shade`
// `shade`:
//   "search"    the texel search (Shypula's option 3, PCSS-like, from the
//               two maps): over a grid of taps as wide as the widest
//               penumbra at the receiver's depth, L·(z_r − D)/D, the nearest
//               tap seen from the penumbra apex (d_out, the way out to the
//               lit side) and the nearest tap hidden from the umbra apex
//               (d_in, the way into the umbra), in world units at the
//               receiver; V = d_in / (d_in + d_out), each at least half a
//               tap, so that a penumbra pixel never reads 0 or 1.
//   "gradient"  Shypula's option 2, a gradient between the two apexes'
//               silhouettes (penumbra_buffer.h): V = 1 − d/Δ, d the distance
//               in the penumbra apex's image to the nearest silhouette edge
//               (the outer boundary), Δ how far inside it the umbra apex's
//               shadow of that edge falls at the receiver's depth (the inner
//               boundary); kept inside [0.001, 0.999].
//   "midpoint"  V = ½ on every penumbra pixel: the classification alone.
// Back-projection of edges (option 1) is not built.
//
// Alpha masks: both maps are drawn through them (common/depth_pass.h), so
// the classification and the search honour them. The gradient's bands come
// from the meshes' edges, where a mask has no place: with `shade: gradient`
// the technique needs opaque casters and is skipped on masked scenes.
//
// Without an umbra apex (a light at least as wide as the casters' extent on
// an axis) there is no umbra map: nothing is umbra, every pixel hidden from
// the penumbra apex is penumbra, and the search takes d_in as the search's
// reach.
//
// The harness records every technique's classes (V = 0, 0 < V < 1, V = 1)
// against the reference's in the record's `classes` (docs/results.md); for
// this technique they are its classification, since its penumbra values
// stay strictly inside (0, 1).
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <memory>
#include <string>
#include <vector>

#include "common/depth_pass.h"
#include "common/light_frame.h"
#include "common/map_lookup.h"
#include "gl/debug.h"
#include "plugin/registry.h"
#include "two_map/apex_placement.h"
#include "two_map/penumbra_buffer.h"

namespace sb::techniques::two_map {
namespace {

// The penumbra apex's map is the lookup's own (shadow_map, light_view…);
// the umbra apex's is on unit 4.
const char* const kTwoMapLookup = R"(
layout(binding = 4) uniform sampler2DShadow umbra_map;
uniform mat4 umbra_view_projection;
uniform mat4 umbra_view;
uniform bool has_umbra_map;
uniform int shade;  // 0: search, 1: gradient, 2: midpoint
uniform int search_radius;
layout(binding = 5) uniform sampler2D penumbra_buffer;
uniform float caster_depth;  // D, from the light's centre along its axis
uniform float light_side;    // the mean of the light's sides
uniform vec2 world_per_uv;   // per unit of depth from each apex: penumbra map, umbra map

float umbra_tap(vec3 t, vec2 gradient, vec2 o) {
  return texture(umbra_map, vec3(t.xy + o, min(t.z + dot(gradient, o), 1.0)));
}

float lit_fraction(vec3 t) {
  bool hidden_p = shadow_tap(t, vec2(0.0)) < 0.5;
  vec3 tu = light_coords(umbra_view_projection, receiver_world);
  bool in_umbra_map = has_umbra_map && all(greaterThanEqual(tu.xy, vec2(0.0))) &&
                      all(lessThanEqual(tu.xy, vec2(1.0)));
  vec2 gu = in_umbra_map && receiver_plane
                ? receiver_plane_gradient(umbra_view_projection, receiver_world, receiver_normal)
                : vec2(0.0);
  bool hidden_u = in_umbra_map && umbra_tap(tu, gu, vec2(0.0)) < 0.5;
  if (!hidden_p && !hidden_u) return 1.0;
  if (hidden_p && hidden_u) return 0.0;
  if (shade == 2) return 0.5;
  float zr = dot(receiver_world - light_centre, light_axis);
  if (shade == 1) {
    // The nearest silhouette edge's point q and its distance d in the
    // penumbra apex's image; E's shadow of q sets the penumbra's width there.
    // No band reached: the pixel lies farther inside than any inner
    // boundary on the farthest receiver, next to the umbra.
    vec4 b = texture(penumbra_buffer, t.xy);
    if (b.w < 0.0) return 1e-3;
    float width = length(inner_image(b.xyz, zr) - apex_image(b.xyz));
    if (!(width > 0.0)) return 0.5;
    return clamp(1.0 - b.w / width, 1e-3, 1.0 - 1e-3);
  }
  float reach = light_side * max(zr - caster_depth, 0.0) / caster_depth;
  if (!(reach > 0.0)) return 0.5;
  // World units at the receiver per uv of each map (their image planes are parallel).
  float wp = world_per_uv.x * -(light_view * vec4(receiver_world, 1.0)).z;
  float wu = world_per_uv.y * -(umbra_view * vec4(receiver_world, 1.0)).z;
  int n = max(search_radius, 1);
  float step = reach / float(n);
  float d_out = reach, d_in = reach;
  for (int y = -n; y <= n; ++y)
    for (int x = -n; x <= n; ++x) {
      vec2 w = vec2(x, y) * step;
      float d = length(w);
      if (d < d_out && shadow_tap(t, w / wp) >= 0.5) d_out = d;
      if (in_umbra_map && d < d_in && umbra_tap(tu, gu, w / wu) < 0.5) d_in = d;
    }
  d_in = max(d_in, 0.5 * step);
  d_out = max(d_out, 0.5 * step);
  return d_in / (d_in + d_out);
}
)";

enum class Shade { Search = 0, Gradient = 1, Midpoint = 2 };

Shade shade_from_string(const std::string& s) {
  if (s == "search") return Shade::Search;
  if (s == "gradient") return Shade::Gradient;
  return Shade::Midpoint;
}

class TwoMapBound final : public Technique {
 public:
  explicit TwoMapBound(const Params& p)
      : settings_(depth_map_settings(p)),
        shade_(shade_from_string(p.get_string("shade"))),
        search_radius_(p.get_int("search_taps") / 2) {}

  void prepare(const FrameInputs& /*in*/) override {
    penumbra_map_ = DepthMap(settings_.size, settings_.depth_format);
    umbra_map_ = DepthMap(settings_.size, settings_.depth_format);
    lookup_ = MapLookupPass("two_map_bound_lookup", std::string(kInnerImageGlsl) + kTwoMapLookup);
    if (shade_ == Shade::Gradient) penumbra_buffer_ = PenumbraBuffer(settings_.size);
    compare_sampler_ = gl::make_sampler(/*linear=*/false, /*compare=*/true, /*border=*/1.0f);
    const gl::Program& program = lookup_.program();
    program.set("shade", static_cast<int>(shade_));
    program.set_if_active("search_radius", search_radius_);
    gl::throw_if_errors("two_map_bound prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    const Scene& scene = *in.scene;
    const LightFrame frame(scene.light);
    TwoApexes apexes;
    LightFrustum penumbra, umbra;
    {
      auto pass = timer.scope("shadow_maps");
      apexes = place_apexes(frame, scene.caster_bounds());
      penumbra = fit_light_frustum(scene, apexes.penumbra_apex, /*widen_for_light=*/false);
      penumbra_map_.render(*in.gpu, penumbra, settings_.cull, settings_.bias);
      if (apexes.has_umbra_apex) {
        umbra = fit_light_frustum(scene, apexes.umbra_apex, /*widen_for_light=*/false);
        umbra_map_.render(*in.gpu, umbra, settings_.cull, settings_.bias);
      }
    }
    // Without an umbra apex the inner boundary is the light centre's shadow.
    const glm::vec3 inner_apex = apexes.has_umbra_apex ? apexes.umbra_apex : scene.light.center;
    if (shade_ == Shade::Gradient) {
      auto pass = timer.scope("penumbra_buffer");
      penumbra_buffer_.render(in, penumbra, inner_apex);
    }
    auto pass = timer.scope("lookup");
    const gl::Program& program = lookup_.program();
    const auto set = [&program](const std::string& name, const auto& value) {
      program.set_if_active(name, value);
    };
    set("umbra_view_projection", umbra.view_projection);
    set("umbra_view", umbra.view);
    set("has_umbra_map", apexes.has_umbra_apex ? 1 : 0);
    set("light_centre", scene.light.center);
    set("light_axis", frame.n);
    set("apex_view", penumbra.view);
    set("inner_apex", inner_apex);
    set("caster_depth", apexes.caster_depth);
    set("light_side", frame.half_width + frame.half_height);
    set("world_per_uv", glm::vec2(2.0f * penumbra.tan_half_fov, 2.0f * umbra.tan_half_fov));
    glBindTextureUnit(4, umbra_map_.texture());
    glBindSampler(4, compare_sampler_.get());
    if (shade_ == Shade::Gradient) glBindTextureUnit(5, penumbra_buffer_.texture());
    // The horizon test (and the normal offset) from the light's centre, as
    // every map technique makes it, not from the penumbra apex.
    LightFrustum centred = penumbra;
    centred.eye = scene.light.center;
    lookup_.draw(in, centred, settings_, penumbra_map_.texture());
    glBindSampler(4, 0);
  }

 private:
  DepthMapSettings settings_;
  Shade shade_;
  int search_radius_;
  DepthMap penumbra_map_;
  DepthMap umbra_map_;
  MapLookupPass lookup_;
  PenumbraBuffer penumbra_buffer_;
  gl::Sampler compare_sampler_;
};

}  // namespace

TechniqueInfo two_map_bound_info() {
  std::vector<ParamSpec> params = {
      choice_param("shade", "search", {"search", "gradient", "midpoint"},
                   "penumbra pixels: search: the texel search in both maps (Shypula's option 3); "
                   "gradient: between the two apexes' silhouettes (option 2, a penumbra buffer; "
                   "needs opaque casters); "
                   "midpoint: V = 1/2 (the classification alone)"),
      odd(int_param("search_taps", 7, 3, 31,
                    "search grid SIDE (odd), not a tap count: side² taps, spread over the widest "
                    "penumbra at the receiver")),
      receiver_plane_param()};
  // On by default: the search's taps reach far from the pixel (as PCSS's).
  params.back().default_value = true;
  for (auto& p : depth_map_params(2048)) params.push_back(std::move(p));
  return {
      .name = "two_map_bound",
      .family = "two_map",
      .summary =
          "Shypula's two-map penumbra bound: hard maps from the penumbra and umbra frusta's "
          "apexes classify lit, umbra and penumbra; the penumbra is shaded by a texel search or a "
          "silhouette gradient",
      // The edges for the gradient's penumbra buffer.
      .needs = Needs{need::kCasterClosedness, need::kSilhouetteEdges},
      .params = std::move(params),
      .create = [](const Params& p) { return std::make_unique<TwoMapBound>(p); },
      // The gradient's edges are the meshes', and a mask's outline is none: on a
      // masked scene every leaf quad's outline would bound a penumbra.
      .needs_of_params =
          [](const Params& p) {
            return p.get_string("shade") == "gradient" ? Needs{need::kOpaqueCasters} : Needs{};
          }};
}

}  // namespace sb::techniques::two_map
