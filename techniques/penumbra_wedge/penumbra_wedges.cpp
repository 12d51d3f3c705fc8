// penumbra_wedges — soft shadow volumes (Akenine-Möller & Assarsson 2002;
// Assarsson & Akenine-Möller 2003) for a rectangular area light:
//
//  1. umbra: stencil shadow volumes from the light's centre, through the
//     shared caster volumes (shadow_volume/caster_volumes.h) with every
//     silhouette mode of Mattausch et al. 2012; V = 1 − the count of
//     volumes around the point (0 in one umbra, 1 outside).
//  2. wedges: one per silhouette edge, the convex hull of every point whose
//     view of the light the edge can cut (wedge_geometry.h), built on the CPU
//     and drawn by its back faces, so each pixel is visited once per wedge
//     and surfaces behind the hull fail the depth test.
//  3. per fragment in a wedge (Lengyel's half-wedge test first): the edge,
//     cut at a local near plane just in front of the point p, is projected
//     from p onto the light's plane and its contribution added into a float
//     buffer: the area of the light in the sector from the light's centre
//     through the projected ends, beyond the projected edge, clipped
//     analytically to the light's rectangle (no lookup table). Summed over a
//     silhouette loop, these terms turn the centre's hard visibility into
//     1 − area(projected silhouette ∩ light) / area(light): the fan of the
//     projected loop about the centre, whose full sectors the umbra counted.
//  4. combine: V = clamp(umbra + Σ terms, 0, 1).
//
// Approximations of the method, measured in docs/penumbra_wedges.md: one
// silhouette, the light centre's, for every light point; overlapping
// silhouettes' occlusion is summed (over-darkening; clamped at 0), which is
// what penumbra_wedges_blend corrects. The umbra's count keeps that sum
// linear: with V = 0 for "in any umbra" instead, a point in two umbrae would
// get both silhouettes' lit parts added back, a light leak.
//
// Where the light's centre lies on a projected edge's line (p on that edge's
// hard shadow boundary, within 1e-3 rad), the sector is a half-plane on
// either side, and rounding decides which; the term is then taken on the
// side that the stencil's umbra test took at this pixel, so the two can
// never disagree by a whole light.
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "gl/debug.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "penumbra_wedge/wedge_geometry.h"
#include "plugin/registry.h"
#include "shadow_volume/caster_volumes.h"

namespace sb {
namespace {

const char* const kWedgeVertex = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in uint wedge;
uniform mat4 view_projection;
flat out uint v_wedge;
void main() {
  v_wedge = wedge;
  gl_Position = view_projection * vec4(position, 1.0);
}
)";

const char* const kWedgeFragment = R"(#version 450 core
flat in uint v_wedge;
layout(binding = 0) uniform sampler2D position_tex;
layout(binding = 1) uniform sampler2D umbra_tex;  // 1 − the stencil's count: 1 outside every umbra
struct Wedge {
  vec4 a, b;  // the edge's ends in the light's frame
  vec4 centre_plane, first_bound, second_bound;
};
layout(std430, binding = 0) readonly buffer Wedges { Wedge wedges[]; };
uniform vec3 light_center;
uniform vec3 light_u;
uniform vec3 light_v;
uniform vec3 light_n;
uniform vec2 half_size;
uniform float orientation;
uniform float half_wedge_tolerance;  // +1 or −1: how silhouette loops wind seen from a shadowed point
out float delta;

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

// Area of the light's rectangle on the non-negative side of three lines
// h.x·x + h.y·y + h.z (Sutherland–Hodgman, then the shoelace formula).
float clipped_area(vec3 h0, vec3 h1, vec3 h2) {
  vec2 poly[8];
  vec2 next[8];
  poly[0] = -half_size;
  poly[1] = vec2(half_size.x, -half_size.y);
  poly[2] = half_size;
  poly[3] = vec2(-half_size.x, half_size.y);
  int n = 4;
  vec3 lines[3] = vec3[3](h0, h1, h2);
  for (int l = 0; l < 3; ++l) {
    int m = 0;
    for (int i = 0; i < n; ++i) {
      vec2 p = poly[i];
      vec2 q = poly[(i + 1) % n];
      float dp = dot(lines[l].xy, p) + lines[l].z;
      float dq = dot(lines[l].xy, q) + lines[l].z;
      if (dp >= 0.0) next[m++] = p;
      if ((dp >= 0.0) != (dq >= 0.0)) next[m++] = mix(p, q, dp / (dp - dq));
    }
    if (m < 3) return 0.0;
    n = m;
    for (int i = 0; i < n; ++i) poly[i] = next[i];
  }
  float twice = 0.0;
  for (int i = 0; i < n; ++i) twice += cross2(poly[i], poly[(i + 1) % n]);
  return 0.5 * twice;
}

// The light's area in the sector from the centre through a, counter-clockwise
// to b (cross(a, b) >= 0), beyond the segment a b.
float beyond_area(vec2 a, vec2 b) {
  vec2 e = b - a;
  return clipped_area(vec3(-a.y, a.x, 0.0), vec3(b.y, -b.x, 0.0),
                      vec3(e.y, -e.x, e.x * a.y - e.y * a.x));
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 pos = texelFetch(position_tex, pixel, 0);
  if (pos.w == 0.0) discard;
  Wedge w = wedges[v_wedge];
  // Lengyel: one plane decides the half, one more whether p is inside it.
  vec4 p4 = vec4(pos.xyz, 1.0);
  vec3 d = pos.xyz - light_center;
  float bound = dot(w.centre_plane, p4) < 0.0 ? dot(w.first_bound, p4) : dot(w.second_bound, p4);
  if (bound < -half_wedge_tolerance * length(d)) discard;

  vec3 p = vec3(dot(d, light_u), dot(d, light_v), dot(d, light_n));
  // The local near plane: only the edge's part between p and the light can
  // cut p's view of it (and beyond it the projection would flip).
  float z_near = p.z * (1.0 - 1e-4);
  vec3 A = w.a.xyz, B = w.b.xyz;
  if (A.z >= z_near && B.z >= z_near) discard;
  if (A.z > z_near) A = mix(A, B, (A.z - z_near) / (A.z - B.z));
  if (B.z > z_near) B = mix(B, A, (B.z - z_near) / (B.z - A.z));
  vec2 a = p.xy + (A.xy - p.xy) * (p.z / (p.z - A.z));
  vec2 b = p.xy + (B.xy - p.xy) * (p.z / (p.z - B.z));
  // A projected edge that misses the light adds nothing.
  if (max(a.x, b.x) <= -half_size.x || min(a.x, b.x) >= half_size.x ||
      max(a.y, b.y) <= -half_size.y || min(a.y, b.y) >= half_size.y)
    discard;

  float turn = cross2(a, b);
  float s = orientation;
  if (turn < 0.0) {
    vec2 t = a;
    a = b;
    b = t;
    s = -s;
  }
  float term = s * beyond_area(a, b);
  if (abs(turn) <= 1e-3 * length(a) * length(b) && dot(a, b) < 0.0) {
    // The centre on the edge's line, between its ends: the other half-plane
    // is as likely; keep the one that agrees with the stencil here (lit:
    // this edge darkens; umbra: it lightens).
    float other = -s * beyond_area(b, a);
    bool lit = texelFetch(umbra_tex, pixel, 0).r > 0.5;
    term = lit ? min(term, other) : max(term, other);
  }
  delta = term / (4.0 * half_size.x * half_size.y);
}
)";

// V from the stencil's count of the volumes around each pixel: 1 − count.
// Each silhouette whose volume holds the point adds its whole light, as
// its wedges add or remove parts of it: V = 1 − Σ occlusion, summed over
// silhouettes (the count is read through a stencil view of the G-buffer's
// depth-stencil texture; counts wrap in 8 bits).
const char* const kUmbraFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D position_tex;
layout(binding = 1) uniform usampler2D stencil_tex;
out float visibility;
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  if (texelFetch(position_tex, pixel, 0).w == 0.0) {
    visibility = 1.0;  // background
    return;
  }
  uint count = texelFetch(stencil_tex, pixel, 0).r;
  visibility = 1.0 - float(count >= 128u ? int(count) - 256 : int(count));
}
)";

const char* const kCombineFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D umbra_tex;
layout(binding = 1) uniform sampler2D delta_tex;
out float visibility;
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  visibility = clamp(texelFetch(umbra_tex, pixel, 0).r + texelFetch(delta_tex, pixel, 0).r, 0.0, 1.0);
}
)";

// How a silhouette loop (wound as the lit region, counter-clockwise seen
// from the light) turns when a point behind it projects it onto the
// light's plane, in the frame (u, v) with n = u × v towards the point.
constexpr float kLoopOrientation = -1.0f;

class PenumbraWedges final : public Technique {
 public:
  explicit PenumbraWedges(const Params& p)
      : offset_(p.get_float("offset")),
        volumes_(volume::count_mode_from_string(p.get_string("mode")), /*cpu=*/true,
                 volume::silhouette_settings(p)) {}

  void prepare(const FrameInputs& in) override {
    volumes_.prepare(in);
    umbra_ =
        gl::Program("penumbra_wedges_umbra", {gl::kFullscreenVertexShader, "", kUmbraFragment});
    umbra_framebuffer_ = gl::make_framebuffer({in.visibility_texture}, 0);
    GLuint view = 0;
    glGenTextures(1, &view);
    glTextureView(view, GL_TEXTURE_2D, in.depth_stencil, GL_DEPTH24_STENCIL8, 0, 1, 0, 1);
    stencil_view_ = gl::Texture(view);
    glTextureParameteri(view, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);
    glTextureParameteri(view, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(view, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    wedge_program_ = gl::Program("penumbra_wedges", {kWedgeVertex, "", kWedgeFragment});
    combine_ =
        gl::Program("penumbra_wedges_combine", {gl::kFullscreenVertexShader, "", kCombineFragment});
    delta_ = gl::make_texture_2d(GL_R32F, in.width, in.height);
    delta_framebuffer_ =
        gl::make_framebuffer({delta_.get()}, in.depth_stencil, GL_DEPTH_STENCIL_ATTACHMENT);
    std::array<GLuint, 3> buffers{};
    glCreateBuffers(3, buffers.data());
    vertices_ = gl::Buffer(buffers[0]);
    indices_ = gl::Buffer(buffers[1]);
    records_ = gl::Buffer(buffers[2]);
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    vao_ = gl::VertexArray(vao);
    glVertexArrayVertexBuffer(vao, 0, vertices_.get(), 0, sizeof(wedge::WedgeVertex));
    glVertexArrayElementBuffer(vao, indices_.get());
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE,
                              offsetof(wedge::WedgeVertex, position));
    glVertexArrayAttribBinding(vao, 0, 0);
    glEnableVertexArrayAttrib(vao, 1);
    glVertexArrayAttribIFormat(vao, 1, 1, GL_UNSIGNED_INT, offsetof(wedge::WedgeVertex, wedge));
    glVertexArrayAttribBinding(vao, 1, 0);
    gl::throw_if_errors("penumbra_wedges prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    const AreaLight& light = in.scene->light;
    {
      auto pass = timer.scope("silhouettes");
      volumes_.choose_zfail(in);
      volumes_.find_silhouettes(light.center);
    }
    {
      auto pass = timer.scope("volumes");
      volumes_.extrude(light.center);
    }
    const wedge::LightFrame frame(light);
    {
      auto pass = timer.scope("wedges");
      build_wedges(frame, frame.farthest(in.scene->bounds()));
    }
    {
      auto pass = timer.scope("upload");
      volumes_.upload();
      // Orphaned and refilled every frame, as dynamic streams.
      glNamedBufferData(vertices_.get(),
                        GLsizeiptr(batch_.vertices.size() * sizeof(wedge::WedgeVertex)),
                        batch_.vertices.data(), GL_STREAM_DRAW);
      glNamedBufferData(indices_.get(), GLsizeiptr(batch_.indices.size() * sizeof(uint32_t)),
                        batch_.indices.data(), GL_STREAM_DRAW);
      glNamedBufferData(records_.get(),
                        GLsizeiptr(batch_.wedges.size() * sizeof(wedge::WedgeRecord)),
                        batch_.wedges.data(), GL_STREAM_DRAW);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glViewport(0, 0, in.width, in.height);
    {
      auto pass = timer.scope("stencil");
      volume::begin_stencil_count(offset_);
      for (const bool zfail : {false, true}) {
        volume::set_stencil_ops(zfail);
        volumes_.draw(in, zfail);
      }
      volume::end_stencil_count();
    }
    {
      auto pass = timer.scope("umbra");
      glDisable(GL_STENCIL_TEST);
      glDisable(GL_DEPTH_TEST);
      glBindFramebuffer(GL_FRAMEBUFFER, umbra_framebuffer_.get());
      umbra_.use();
      glBindTextureUnit(0, in.gbuffer_position);
      glBindTextureUnit(1, stencil_view_.get());
      gl::draw_fullscreen_triangle();
      glBindTextureUnit(1, 0);
    }
    {
      auto pass = timer.scope("penumbra");
      draw_wedges(in, frame);
    }
    auto pass = timer.scope("combine");
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glTextureBarrier();  // each pixel reads its own umbra value, then writes V
    combine_.use();
    glBindTextureUnit(0, in.visibility_texture);
    glBindTextureUnit(1, delta_.get());
    gl::draw_fullscreen_triangle();
  }

 private:
  // One wedge per edge of every silhouette loop (the smooth positions: the
  // curve the volume's sides start from).
  void build_wedges(const wedge::LightFrame& frame, float scene_far) {
    batch_.clear();
    if (scene_far <= 0.0f) return;  // the whole scene behind the light
    const wedge::WedgeRange range = wedge::wedge_range(scene_far);
    for (const volume::Silhouette& s : volumes_.silhouettes())
      for (const auto& loop : s.loops)
        for (size_t i = 0; i < loop.size(); ++i)
          wedge::append_wedge(frame, loop[i].smooth, loop[(i + 1) % loop.size()].smooth, range,
                              batch_);
  }

  void draw_wedges(const FrameInputs& in, const wedge::LightFrame& frame) {
    glBindFramebuffer(GL_FRAMEBUFFER, delta_framebuffer_.get());
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearBufferfv(GL_COLOR, 0, zero);
    if (batch_.indices.empty()) return;
    // Back faces only, each pixel once per wedge; the hull's exit point must
    // lie at or behind the surface (a surface behind the wedge is outside
    // it), and the hull reaches past the far plane (depth clamp).
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GEQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_DEPTH_CLAMP);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    wedge_program_.use();
    wedge_program_.set("view_projection", in.view_projection);
    wedge_program_.set("light_center", frame.center);
    wedge_program_.set("light_u", frame.u);
    wedge_program_.set("light_v", frame.v);
    wedge_program_.set("light_n", frame.n);
    wedge_program_.set("half_size", glm::vec2(frame.half_width, frame.half_height));
    wedge_program_.set("orientation", kLoopOrientation);
    wedge_program_.set("half_wedge_tolerance", wedge::kHalfWedgeTolerance);
    glBindTextureUnit(0, in.gbuffer_position);
    glBindTextureUnit(1, in.visibility_texture);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, records_.get());
    glBindVertexArray(vao_.get());
    glDrawElements(GL_TRIANGLES, GLsizei(batch_.indices.size()), GL_UNSIGNED_INT, nullptr);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_CULL_FACE);
    glDepthFunc(GL_LESS);
  }

  float offset_;
  volume::CasterVolumes volumes_;
  wedge::WedgeBatch batch_;
  gl::Program umbra_;
  gl::Program wedge_program_;
  gl::Program combine_;
  gl::Texture delta_;
  gl::Framebuffer delta_framebuffer_;
  gl::Framebuffer umbra_framebuffer_;
  gl::Texture stencil_view_;  // the G-buffer's depth-stencil, read as stencil counts
  gl::Buffer vertices_;
  gl::Buffer indices_;
  gl::Buffer records_;
  gl::VertexArray vao_;
};

}  // namespace
}  // namespace sb

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  using namespace sb;
  TechniqueInfo info{
      "penumbra_wedges",
      "penumbra_wedge",
      "soft shadow volumes (Akenine-Möller & Assarsson 2002): an umbra from the light centre's "
      "shadow volumes, then one wedge per silhouette edge whose fragments add the light area "
      "that the edge, projected from the point, uncovers or covers (analytic clipping to the "
      "rectangle)",
      Needs{need::kClosedCasters, need::kOpaqueCasters, need::kCasterEdges},
      {choice_param("mode", "zfail", {"zpass", "zfail", "auto"},
                    "umbra volumes: zpass counts in front of the surface; zfail behind (robust); "
                    "auto uses zfail only for casters whose volume can reach the camera's near "
                    "plane"),
       float_param("offset", 1.0, -1e6, 1e6,
                   "glPolygonOffset units pushing umbra volume faces away from the camera")},
      [](const Params& p) { return std::make_unique<PenumbraWedges>(p); }};
  for (ParamSpec& spec : volume::silhouette_params(
           "the light centre's silhouette (shadow_volume's modes, Mattausch et al. 2012); the "
           "wedges follow the same loops"))
    info.params.push_back(std::move(spec));
  registry.add(std::move(info));
}
