// plateaus — Haines 2001, "Soft planar shadows using plateaus": the hard
// planar shadow from the light's centre (Blinn's projection, as `planar`),
// then, around every silhouette edge seen from that centre, a penumbra
// region drawn on the receiver plane whose width grows with the occluder's
// distance from the plane, shaded from full shadow at the hard shadow's
// border to lit at its outer edge. Haines draws cones at the silhouette's
// vertices and sheets along its edges into the Z-buffer, so that the
// darkest one wins; here every edge draws one band (common/silhouette_band.h)
// on its lit side, whose fragments take the light-shaped distance g from the
// flattened edge, and MIN blending keeps the darkest.
//
// Per flattened edge point P of an occluder point a, ρ = |P − a| / |a − l|
// = h_a / (H − h_a) (heights above the plane of a and of the light's centre
// l): the light's rectangle, projected onto the plane along its normal and
// scaled by ρ, is the shadow of a point light moving over it, so a plane
// point p is in a's outer penumbra iff its light-shaped distance g from P is
// at most ρ, and V = g / ρ there (linear across the penumbra, ρ interpolated
// along the edge). This is exact in extent for a straight edge parallel to
// a light parallel to the plane. A light at a slant to the plane, turned
// about its normal, projects to a parallelogram, not a rectangle: g is
// max(|α|, |β|) for p − P = α·hu + β·hv, solved in the projected axes
// (common/silhouette_band.h).
//
// The paper's footprint and ours: Haines's cones are round, the penumbra of
// a disc whose radius grows with the occluder's height, whatever the
// light's shape; here the footprint is the light's own, the projected
// parallelogram (cones become parallelograms, sheets the light's support
// function wide), since the harness's lights are rectangles and the
// reference integrates over them. The round cone is not built.
//
// What it leaves out, on purpose: the inner half of the penumbra (the hard
// shadow stays the umbra, so shadows are too large and too dark; the
// "outer penumbra only" of docs/survey_techniques.md); any receiver but the
// plane (other pixels get V = 1, as with `planar`); the parts of casters at
// or above the light's height (their edges draw no band); a light seen
// edge-on from the plane (its projection has no area: no bands). The light
// is projected along the plane's normal; the ray from an occluder point not
// under the light's centre would shear it further, and the light's points
// off the centre's height scale it unevenly (both first order in the
// light's slant; neither is modelled).
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include "planar/plateaus.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "common/light_frame.h"
#include "common/silhouette_band.h"
#include "core/error.h"
#include "gl/debug.h"
#include "gl/gpu_scene.h"
#include "gl/program.h"
#include "planar/projected_shadow.h"
#include "plugin/registry.h"

namespace sb::techniques::planar {

using core::JobError;
using gl::DrawInfo;

namespace {

const char* const kBandVertex = R"(
uniform mat4 view_projection;
uniform vec3 light_center;
uniform vec4 receiver_plane;  // n·x + d = 0, n towards the casters
uniform vec3 plane_origin;    // a point of the plane
uniform vec3 plane_e1, plane_e2;
uniform vec2 light_hu, light_hv;  // the light's half axes on the plane (e1, e2)
flat out vec2 a_plane, b_plane;
flat out vec2 ratios;         // ρ at a and b
flat out vec2 outward;
out gl_PerVertex { vec4 gl_Position; };

vec2 on_plane(vec3 x) { return vec2(dot(x - plane_origin, plane_e1), dot(x - plane_origin, plane_e2)); }

void main() {
  Edge e = edges[gl_VertexID / kBandVertices];
  float hl = dot(receiver_plane, vec4(light_center, 1.0));
  float ha = dot(receiver_plane, vec4(e.p0.xyz, 1.0)), hb = dot(receiver_plane, vec4(e.p1.xyz, 1.0));
  // Edges reaching the light's height, or below the plane, cast no band.
  if (!on_silhouette(e, light_center) || ha >= hl || hb >= hl || ha < 0.0 || hb < 0.0) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
  // Flattened from the light's centre: P = l + (x − l) · H / (H − h).
  vec3 pa = light_center + (e.p0.xyz - light_center) * hl / (hl - ha);
  vec3 pb = light_center + (e.p1.xyz - light_center) * hl / (hl - hb);
  a_plane = on_plane(pa);
  b_plane = on_plane(pb);
  ratios = vec2(ha / (hl - ha), hb / (hl - hb));
  // The occluder's side on the plane: the flattening's derivative at the
  // middle along the direction into the lit face.
  vec3 m = 0.5 * (e.p0.xyz + e.p1.xyz), d = into_lit_face(e, light_center);
  float hm = dot(receiver_plane, vec4(m, 1.0)), dh = dot(receiver_plane.xyz, d);
  vec3 pm = light_center + (m - light_center) * hl / (hl - hm);
  vec3 dp = (hl * d - dh * (light_center - pm)) / (hl - hm);
  vec2 inside = vec2(dot(dp, plane_e1), dot(dp, plane_e2));
  outward = outward_normal(a_plane, b_plane, inside);
  float reach = (length(light_hu) + length(light_hv)) * max(ratios.x, ratios.y);
  vec2 c = band_corner(a_plane, b_plane, reach, outward, gl_VertexID % kBandVertices);
  gl_Position = view_projection * vec4(plane_origin + c.x * plane_e1 + c.y * plane_e2, 1.0);
}
)";

const char* const kBandFragment = R"(
layout(binding = 0) uniform sampler2D position_tex;
uniform vec4 receiver_plane;
uniform float on_plane_tolerance;
uniform vec3 plane_origin;
uniform vec3 plane_e1, plane_e2;
uniform vec2 light_hu, light_hv;
flat in vec2 a_plane, b_plane;
flat in vec2 ratios;
flat in vec2 outward;
out float visibility;
void main() {
  vec4 p = texelFetch(position_tex, ivec2(gl_FragCoord.xy), 0);
  if (p.w == 0.0 || abs(dot(receiver_plane.xyz, p.xyz) + receiver_plane.w) > on_plane_tolerance)
    discard;
  vec2 q = vec2(dot(p.xyz - plane_origin, plane_e1), dot(p.xyz - plane_origin, plane_e2));
  if (dot(q - a_plane, outward) < 0.0) discard;  // the hard shadow's side
  float t;
  visibility = min(1.0, light_ratio(q, a_plane, b_plane, light_hu, light_hv, ratios.x, ratios.y, t));
}
)";

class Plateaus final : public Technique {
 public:
  void prepare(const FrameInputs& in) override {
    if (!in.has_receiver_plane) throw JobError("plateaus: the scene has no planar receiver");
    tolerance_ = 1e-4f * std::max(in.scene->bounds().radius(), 1e-6f);
    project_ = gl::Program("plateaus_project", {kProjectVertex, "", kProjectFragment});
    bands_ = gl::Program(
        "plateaus_bands",
        {std::string("#version 450 core\n") + kSilhouetteBandVertexGlsl + kBandVertex, "",
         std::string("#version 450 core\n") + kSilhouetteBandFragmentGlsl + kBandFragment});
    // The plane's own frame: scene geometry, not the light.
    const glm::vec3 n(in.receiver_plane);
    const glm::vec3 across = std::fabs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    e1_ = glm::normalize(glm::cross(n, across));
    e2_ = glm::cross(n, e1_);
    origin_ = -in.receiver_plane.w * n;
    gl::throw_if_errors("plateaus prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    const AreaLight& light = in.scene->light;
    {
      auto pass = timer.scope("clear");
      glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
      glViewport(0, 0, in.width, in.height);
      const float lit[4] = {1.0f, 1.0f, 1.0f, 1.0f};
      glClearBufferfv(GL_COLOR, 0, lit);
    }
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_MIN);  // the darkest of the hard shadow and every band
    glBindTextureUnit(0, in.gbuffer_position);
    // A light at or below the plane lights nothing on the casters' side.
    if (glm::dot(in.receiver_plane, glm::vec4(light.center, 1.0f)) > 0.0f) {
      {
        auto pass = timer.scope("hard_shadow");
        glEnable(GL_CLIP_DISTANCE0);
        project_.use();
        project_.set("view_projection", in.view_projection);
        project_.set("receiver_plane", in.receiver_plane);
        project_.set("on_plane_tolerance", tolerance_);
        project_.set("darkening_value", 0.0f);
        project_.set("shadow_projection", planar_projection(in.receiver_plane, light.center));
        glDisable(GL_CULL_FACE);
        in.gpu->draw_casters([](const DrawInfo&) {});
        glDisable(GL_CLIP_DISTANCE0);
      }
      auto pass = timer.scope("plateaus");
      const glm::vec2 hu = on_plane(light.half_u), hv = on_plane(light.half_v);
      // A light without area, or seen edge-on from the plane, has no penumbra here.
      const float area = std::fabs(hu.x * hv.y - hu.y * hv.x);
      if (LightFrame(light).has_area() && area > 1e-12f * glm::dot(hu + hv, hu + hv)) {
        bands_.use();
        bands_.set("view_projection", in.view_projection);
        bands_.set("light_center", light.center);
        bands_.set("receiver_plane", in.receiver_plane);
        bands_.set("on_plane_tolerance", tolerance_);
        bands_.set("plane_origin", origin_);
        bands_.set("plane_e1", e1_);
        bands_.set("plane_e2", e2_);
        bands_.set("light_hu", hu);
        bands_.set("light_hv", hv);
        draw_silhouette_bands(in);
      }
    }
    glDisable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glDepthMask(GL_TRUE);
  }

 private:
  // A vector in the plane's frame, projected along its normal.
  glm::vec2 on_plane(const glm::vec3& v) const { return {glm::dot(v, e1_), glm::dot(v, e2_)}; }

  float tolerance_ = 0.0f;
  glm::vec3 e1_{1, 0, 0}, e2_{0, 0, 1}, origin_{0.0f};
  gl::Program project_;
  gl::Program bands_;
};

}  // namespace

TechniqueInfo plateaus_info() {
  return {.name = "plateaus",
          .family = "planar",
          .summary =
              "Haines's plateaus: the hard planar shadow plus penumbra bands on the receiver plane "
              "around the light centre's silhouette edges, as wide as the occluder's height sets; "
              "outer penumbra only",
          .needs = Needs{need::kRectangularLight, need::kPlanarReceiver, need::kOpaqueCasters,
                         need::kSilhouetteEdges},
          .params = {},
          .create = [](const Params&) { return std::make_unique<Plateaus>(); }};
}

}  // namespace sb::techniques::planar
