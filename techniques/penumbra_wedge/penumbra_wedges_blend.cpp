// penumbra_wedges_blend — penumbra-wedge blending (Forest, Barthe & Paulin
// 2006): plain penumbra wedges (penumbra_wedges.cpp) add every silhouette's
// occlusion, so where two silhouettes cover the same part of the light the
// point is darkened twice. Here each silhouette (one per caster) is rendered
// on its own, and blended into the result with an estimate of the overlap.
//
// Per silhouette s, in its screen rectangle (the scissor: the projection of
// its wedges' hulls, which hold its umbra too), into float MRTs:
//  - its umbra from its own volume in the stencil: c_s, the count of its
//    loops that hide the light's centre (a caster may have several, and
//    they may overlap; the merge reads the count, not just "hidden");
//  - its wedges, adding per quadrant of the light (the light split at its
//    centre into four radial parts) the fan terms of penumbra_wedges; the
//    quadrant's occluded area is then A = c_s·|L_q| − Σ terms (with c_s
//    corrected where rounding put the centre on the other side of an edge
//    than the stencil did: see the merge shader);
//  - the bounding rectangle of the occluded part of each quadrant: the
//    projected edges' pieces inside it (max blending), and the quadrant's
//    lattice points (corners, mid-sides, centre) that the silhouette
//    covers, counted with the same fan (winding = c_s − Σ signed counts).
//    This is our form of the paper's "max X and Y of the edges" with its
//    inner-wedge adjustment: it also holds when the centre is hidden.
// Then blended into the accumulated buffers (per quadrant an area and a
// rectangle), read and written in place: with occluded areas A_f (so far)
// and A_s, bounding rectangles of areas B_f and B_s, and β the area of
// their intersection, the overlap is estimated as uniform densities,
//   ε = (A_f / B_f)·(A_s / B_s)·β,
// and A = min(A_f + A_s − ε, |L_q|); the rectangles are merged. A pixel that
// the silhouette leaves unoccluded is skipped (the merge discards it).
// Last, V = 1 − Σ_q A_q / |L|.
//
// Storage is float MRTs (8 for a silhouette, 5 accumulated); the paper's
// 8-bit packing is not offered. One silhouette per caster: the loops of one
// caster are added, as in penumbra_wedges.
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "gl/debug.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "penumbra_wedge/silhouette_wedges.h"
#include "penumbra_wedge/wedge_stream.h"
#include "penumbra_wedge/wedge_variants.h"
#include "plugin/registry.h"
#include "shadow_volume/caster_volumes.h"

namespace sb::techniques::penumbra_wedge {
namespace {

// Quadrants q = 0..3: signs (+,+), (−,+), (−,−), (+,−). Mid-sides m = 0..3:
// (+x, 0), (0, +y), (−x, 0), (0, −y).
const char* const kQuadrantGlsl = R"(
const vec2 kQuadrant[4] = vec2[4](vec2(1, 1), vec2(-1, 1), vec2(-1, -1), vec2(1, -1));
)";

const char* const kSilhouetteMain = R"(
layout(binding = 0) uniform sampler2D position_tex;
layout(location = 0) out vec4 quadrant_terms;  // Σ fan terms per quadrant, / |L|
layout(location = 1) out vec4 corner_counts;   // Σ s·[corner q in the term's region]
layout(location = 2) out vec4 middle_counts;   // Σ s·[mid-side m in the term's region]
layout(location = 3) out vec4 edge_box[4];     // (max x, max y, −min x, −min y) per quadrant
layout(location = 7) out float near_centre;    // 1: an edge passes the light's centre here

bool in_region(vec2 a, vec2 b, vec2 x) {
  vec2 e = b - a;
  return cross2(a, x) >= 0.0 && cross2(x, b) >= 0.0 && cross2(e, x - a) <= 0.0;
}

// Adds ½ cross(p, q), the fan triangle of the piece p q about the centre, to
// the quadrant the piece lies in.
void add_piece(vec2 p, vec2 q, inout vec4 area) {
  vec2 m = 0.5 * (p + q);
  int k = m.x >= 0.0 ? (m.y >= 0.0 ? 0 : 3) : (m.y >= 0.0 ? 1 : 2);
  area[k] += 0.5 * cross2(p, q);
}

void add_fan(vec2 p, vec2 q, inout vec4 area) {
  float tx = (p.x < 0.0) != (q.x < 0.0) ? p.x / (p.x - q.x) : 1.0;
  float ty = (p.y < 0.0) != (q.y < 0.0) ? p.y / (p.y - q.y) : 1.0;
  vec2 m1 = mix(p, q, min(tx, ty)), m2 = mix(p, q, max(tx, ty));
  add_piece(p, m1, area);
  add_piece(m1, m2, area);
  add_piece(m2, q, area);
}

// beyond_area's region (kWedgeGlsl) split into the four quadrants: each
// piece of its fan about the centre, split where it crosses the axes, lies
// in one quadrant.
vec4 beyond_quadrants(vec2 a, vec2 b) {
  vec4 area = vec4(0.0);
  vec2 p0, p1;
  if (!clip_segment(a, b, -half_size, half_size, p0, p1)) return area;
  int s0, s1;
  vec2 cur = boundary_exit(p0, s0), end = boundary_exit(p1, s1);
  add_fan(p1, p0, area);
  for (int step = 0; step < 4; ++step)
    if (s0 != s1) {
      vec2 k = kCorner[s0] * half_size;
      add_fan(cur, k, area);
      cur = k;
      s0 = (s0 + 1) % 4;
    }
  add_fan(cur, end, area);
  return area;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 pos = texelFetch(position_tex, pixel, 0);
  vec2 a, b;
  float s;
  if (pos.w == 0.0 || !fan_edge(pos.xyz, a, b, s)) discard;
  near_centre = centre_on_edge(a, b) ? 1.0 : 0.0;
  float light_area = 4.0 * half_size.x * half_size.y;
  vec4 area = beyond_quadrants(a, b);
  for (int q = 0; q < 4; ++q) {
    vec2 q_lo = min(vec2(0.0), kQuadrant[q] * half_size), q_hi = max(vec2(0.0), kQuadrant[q] * half_size);
    quadrant_terms[q] = s * area[q] / light_area;
    corner_counts[q] = in_region(a, b, kQuadrant[q] * half_size) ? s : 0.0;
    vec2 p, r;
    edge_box[q] = clip_segment(a, b, q_lo, q_hi, p, r) ? vec4(max(p, r), -min(p, r)) : vec4(-1e30);
  }
  vec2 middles[4] = vec2[4](vec2(half_size.x, 0), vec2(0, half_size.y), vec2(-half_size.x, 0),
                            vec2(0, -half_size.y));
  for (int m = 0; m < 4; ++m) middle_counts[m] = in_region(a, b, middles[m]) ? s : 0.0;
}
)";

const char* const kMergeFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D position_tex;
layout(binding = 1) uniform sampler2D terms_tex;
layout(binding = 2) uniform sampler2D corners_tex;
layout(binding = 3) uniform sampler2D middles_tex;
layout(binding = 4) uniform sampler2D edge_box_tex[4];
layout(binding = 8) uniform sampler2D area_tex;
layout(binding = 9) uniform sampler2D rect_tex[4];
layout(binding = 13) uniform usampler2D stencil_tex;  // this silhouette's volume count
layout(binding = 14) uniform sampler2D near_centre_tex;
uniform vec2 half_size;
layout(location = 0) out vec4 area_out;     // occluded area per quadrant, / |L|
layout(location = 1) out vec4 rect_out[4];  // (min x, min y, max x, max y) per quadrant
)"
                                   R"(
float rect_area(vec4 r) { return max(r.z - r.x, 0.0) * max(r.w - r.y, 0.0); }
vec4 include_point(vec4 r, vec2 p) { return vec4(min(r.xy, p), max(r.zw, p)); }

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  if (texelFetch(position_tex, pixel, 0).w == 0.0) discard;
  float quarter = 0.25;
  // The silhouette's winding about the light's centre, from its stencil:
  // where the centre lies on a projected edge, rounding may have put the
  // edge's term on the other side than the stencil, which moves every
  // quadrant by a whole quarter (and every lattice point by one turn). Where
  // an edge passes the centre here (its wedges flagged it), all four
  // quadrants at or below 0 with one well below, or at or above a quarter
  // with one well above, is that rounding, and the winding is corrected.
  // Elsewhere such values are the silhouette's own (loops of one caster that
  // overlap, a loop that crosses itself seen from the point) and are left to
  // the clamp.
  float winding = stencil_count(stencil_tex, pixel);
  vec4 raw = winding * quarter - texelFetch(terms_tex, pixel, 0);
  if (texelFetch(near_centre_tex, pixel, 0).r > 0.5) {
    if (all(lessThanEqual(raw, vec4(1e-4))) && any(lessThan(raw, vec4(-0.05))))
      winding += 1.0;
    else if (all(greaterThanEqual(raw, vec4(quarter - 1e-4))) &&
             any(greaterThan(raw, vec4(quarter + 0.05))))
      winding -= 1.0;
  }
  vec4 occluded = clamp(winding * quarter - texelFetch(terms_tex, pixel, 0), 0.0, quarter);
  // Dynamic skip: this silhouette hides nothing of the light here.
  if (all(lessThanEqual(occluded, vec4(1e-7)))) discard;
  vec4 corners_in = vec4(winding) - texelFetch(corners_tex, pixel, 0);
  vec4 middles_in = vec4(winding) - texelFetch(middles_tex, pixel, 0);
  vec2 middles[4] = vec2[4](vec2(half_size.x, 0), vec2(0, half_size.y), vec2(-half_size.x, 0),
                            vec2(0, -half_size.y));
  vec4 area = texelFetch(area_tex, pixel, 0);
  float light_area = 4.0 * half_size.x * half_size.y;
  for (int q = 0; q < 4; ++q) {
    vec4 so_far = texelFetch(rect_tex[q], pixel, 0);
    area_out[q] = area[q];
    rect_out[q] = so_far;
    if (occluded[q] <= 1e-7) continue;
    // This silhouette's rectangle: its edges' pieces and the covered lattice points.
    vec4 box = texelFetch(edge_box_tex[q], pixel, 0);
    vec4 mine = box.x > -1e29 ? vec4(-box.zw, box.xy) : vec4(1e30, 1e30, -1e30, -1e30);
    vec2 corner = kQuadrant[q] * half_size;
    if (winding > 0.5) mine = include_point(mine, vec2(0.0));
    if (corners_in[q] > 0.5) mine = include_point(mine, corner);
    int mx = kQuadrant[q].x > 0.0 ? 0 : 2, my = kQuadrant[q].y > 0.0 ? 1 : 3;
    if (middles_in[mx] > 0.5) mine = include_point(mine, middles[mx]);
    if (middles_in[my] > 0.5) mine = include_point(mine, middles[my]);
    if (mine.x > mine.z) mine = vec4(min(vec2(0.0), corner), max(vec2(0.0), corner));
    if (area[q] <= 1e-7) {
      area_out[q] = occluded[q];
      rect_out[q] = mine;
      continue;
    }
    // Forest et al.: the overlap as if each occluded area were spread
    // evenly over its rectangle.
    float b_f = rect_area(so_far), b_s = rect_area(mine);
    float beta = rect_area(vec4(max(so_far.xy, mine.xy), min(so_far.zw, mine.zw)));
    float eps = 0.0;
    if (b_f > 0.0 && b_s > 0.0)
      eps = (area[q] * light_area / b_f) * (occluded[q] * light_area / b_s) * beta / light_area;
    eps = min(eps, min(area[q], occluded[q]));
    area_out[q] = min(area[q] + occluded[q] - eps, quarter);
    rect_out[q] = vec4(min(so_far.xy, mine.xy), max(so_far.zw, mine.zw));
  }
}
)";

const char* const kResolveFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D position_tex;
layout(binding = 1) uniform sampler2D area_tex;
out float visibility;
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 a = texelFetch(area_tex, pixel, 0);
  visibility = texelFetch(position_tex, pixel, 0).w == 0.0 ? 1.0 : clamp(1.0 - (a.x + a.y + a.z + a.w), 0.0, 1.0);
}
)";

constexpr int kSilhouetteTargets = 8;   // terms, corners, middles, 4 edge boxes, centre flag
constexpr int kAccumulatedTargets = 5;  // areas, 4 rectangles

class PenumbraWedgesBlend final : public Technique {
 public:
  explicit PenumbraWedgesBlend(const Params& p) : offset_(p.get_float("offset")), wedges_(p) {}

  void prepare(const FrameInputs& in) override {
    wedges_.prepare(in);
    const std::string header = std::string("#version 450 core\n") + kWedgeGlsl + kQuadrantGlsl;
    silhouette_program_ = gl::Program("penumbra_wedges_blend_silhouette",
                                      {kWedgeVertex, "", header + kSilhouetteMain});
    std::string merge = kMergeFragment;
    merge.insert(merge.find('\n') + 1, std::string(kQuadrantGlsl) + kStencilCountGlsl);
    merge_ = gl::Program("penumbra_wedges_blend_merge", {gl::kFullscreenVertexShader, "", merge});
    resolve_ = gl::Program("penumbra_wedges_blend_resolve",
                           {gl::kFullscreenVertexShader, "", kResolveFragment});
    for (gl::Texture& t : silhouette_targets_)
      t = gl::make_texture_2d(GL_RGBA32F, in.width, in.height);
    for (gl::Texture& t : accumulated_) t = gl::make_texture_2d(GL_RGBA32F, in.width, in.height);
    silhouette_framebuffer_ = gl::make_framebuffer(
        {silhouette_targets_[0].get(), silhouette_targets_[1].get(), silhouette_targets_[2].get(),
         silhouette_targets_[3].get(), silhouette_targets_[4].get(), silhouette_targets_[5].get(),
         silhouette_targets_[6].get(), silhouette_targets_[7].get()},
        in.depth_stencil, GL_DEPTH_STENCIL_ATTACHMENT);
    // No depth-stencil here: the merge reads the silhouette's stencil counts.
    accumulated_framebuffer_ =
        gl::make_framebuffer({accumulated_[0].get(), accumulated_[1].get(), accumulated_[2].get(),
                              accumulated_[3].get(), accumulated_[4].get()},
                             0);
    stencil_view_ = make_stencil_view(in.depth_stencil);
    gl::throw_if_errors("penumbra_wedges_blend prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    wedges_.build(in, timer);
    glViewport(0, 0, in.width, in.height);
    {
      auto pass = timer.scope("blend");
      glBindFramebuffer(GL_FRAMEBUFFER, accumulated_framebuffer_.get());
      const std::array<float, 4> zero{0.0f, 0.0f, 0.0f, 0.0f};
      glClearBufferfv(GL_COLOR, 0, zero.data());  // no area occluded yet
      // What every silhouette's passes share: uniforms, and the textures on
      // the units the programs read (a program never reads the targets it
      // draws into).
      set_wedge_uniforms(silhouette_program_, wedges_.frame(), in.view_projection);
      merge_.set("half_size", glm::vec2(wedges_.frame().half_width, wedges_.frame().half_height));
      glBindTextureUnit(0, in.gbuffer_position);
      for (int k = 0; k < 7; ++k)
        glBindTextureUnit(GLuint(1 + k), silhouette_targets_[size_t(k)].get());
      for (int k = 0; k < kAccumulatedTargets; ++k)
        glBindTextureUnit(GLuint(8 + k), accumulated_[size_t(k)].get());
      glBindTextureUnit(13, stencil_view_.get());
      glBindTextureUnit(14, silhouette_targets_[7].get());
      for (size_t i = 0; i < wedges_.caster_wedges().size(); ++i) {
        std::array<int, 4> scissor{};
        if (screen_rectangle(in, wedges_.caster_wedges()[i], scissor))
          blend_silhouette(in, i, scissor);
      }
      glDisable(GL_SCISSOR_TEST);
      glDisable(GL_STENCIL_TEST);
      glBindTextureUnit(13, 0);  // the depth-stencil is the visibility target's too
    }
    auto pass = timer.scope("resolve");
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glTextureBarrier();
    resolve_.use();
    glBindTextureUnit(0, in.gbuffer_position);
    glBindTextureUnit(1, accumulated_[0].get());
    gl::draw_fullscreen_triangle();
  }

 private:
  // The screen rectangle (x, y, width, height) of a silhouette's wedge
  // hulls, which hold its umbra too: the whole screen when a hull vertex
  // lies behind the camera; false when empty or off screen.
  bool screen_rectangle(const FrameInputs& in, const IndexRange& wedges,
                        std::array<int, 4>& scissor) const {
    if (wedges.count == 0) {  // its umbra alone (a point light): wherever it falls
      scissor = {0, 0, in.width, in.height};
      return true;
    }
    glm::vec2 lo(1e30f), hi(-1e30f);
    bool behind = false;
    const auto& vertices = wedges_.batch().vertices;
    for (uint32_t v = wedges.first; v < wedges.first + wedges.count && !behind; ++v) {
      const glm::vec4 clip = in.view_projection * glm::vec4(vertices[v].position, 1.0f);
      if (clip.w <= 1e-6f * (std::abs(clip.x) + std::abs(clip.y) + 1e-6f)) {
        behind = true;
        break;
      }
      const glm::vec2 ndc = glm::vec2(clip) / clip.w;
      lo = glm::min(lo, ndc);
      hi = glm::max(hi, ndc);
    }
    const glm::vec2 size(float(in.width), float(in.height));
    const glm::vec2 px_lo = behind ? glm::vec2(0.0f) : (lo * 0.5f + 0.5f) * size - 1.0f;
    const glm::vec2 px_hi = behind ? size : (hi * 0.5f + 0.5f) * size + 1.0f;
    const int x0 = std::clamp(int(std::floor(px_lo.x)), 0, in.width);
    const int y0 = std::clamp(int(std::floor(px_lo.y)), 0, in.height);
    const int x1 = std::clamp(int(std::ceil(px_hi.x)), 0, in.width);
    const int y1 = std::clamp(int(std::ceil(px_hi.y)), 0, in.height);
    scissor = {x0, y0, x1 - x0, y1 - y0};
    return x1 > x0 && y1 > y0;
  }

  void blend_silhouette(const FrameInputs& in, size_t caster, const std::array<int, 4>& scissor) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(scissor[0], scissor[1], scissor[2], scissor[3]);
    glBindFramebuffer(GL_FRAMEBUFFER, silhouette_framebuffer_.get());
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    const std::array<float, 4> zero{0.0f, 0.0f, 0.0f, 0.0f};
    const std::array<float, 4> empty{-1e30f, -1e30f, -1e30f, -1e30f};
    for (int k = 0; k < kSilhouetteTargets; ++k)
      glClearBufferfv(GL_COLOR, k, k < 3 ? zero.data() : empty.data());
    // This silhouette's umbra alone, in the stencil.
    shadow_volume::begin_stencil_count(offset_);
    wedges_.volumes().draw_caster(in, caster);
    shadow_volume::end_stencil_count();
    // Its wedges.
    begin_hull_draw();
    for (int k = 0; k < kSilhouetteTargets; ++k) {
      glEnablei(GL_BLEND, GLuint(k));
      glBlendEquationi(GLuint(k), k < 3 ? GL_FUNC_ADD : GL_MAX);
      glBlendFunci(GLuint(k), GL_ONE, GL_ONE);
    }
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glDisable(GL_STENCIL_TEST);
    silhouette_program_.use();
    wedges_.stream().bind();
    WedgeStream::draw(wedges_.caster_wedges()[caster]);
    for (int k = 0; k < kSilhouetteTargets; ++k) glDisablei(GL_BLEND, GLuint(k));
    end_hull_draw();
    // Blend into the accumulated buffers, each pixel reading its own texels.
    glBindFramebuffer(GL_FRAMEBUFFER, accumulated_framebuffer_.get());
    glTextureBarrier();
    merge_.use();
    gl::draw_fullscreen_triangle();
    glTextureBarrier();
  }

  float offset_;
  SilhouetteWedges wedges_;
  gl::Program silhouette_program_;
  gl::Program merge_;
  gl::Program resolve_;
  std::array<gl::Texture, kSilhouetteTargets> silhouette_targets_;
  std::array<gl::Texture, kAccumulatedTargets> accumulated_;
  gl::Framebuffer silhouette_framebuffer_;
  gl::Framebuffer accumulated_framebuffer_;
  gl::Texture stencil_view_;  // the G-buffer's depth-stencil, read as stencil counts
};

}  // namespace

TechniqueInfo penumbra_wedges_blend_info() {
  return {.name = "penumbra_wedges_blend",
          .family = "penumbra_wedge",
          .summary =
              "penumbra-wedge blending (Forest, Barthe & Paulin 2006): each silhouette's wedges "
              "into its own buffers (occluded area and bounding rectangle per quadrant of the "
              "light), blended with an estimate of the overlap instead of summed",
          .needs = Needs{need::kRectangularLight, need::kClosedCasters, need::kOpaqueCasters,
                         need::kCasterEdges},
          .params = umbra_params(),
          .create = [](const Params& p) { return std::make_unique<PenumbraWedgesBlend>(p); }};
}

}  // namespace sb::techniques::penumbra_wedge
