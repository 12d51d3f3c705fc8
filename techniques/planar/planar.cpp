// planar — Blinn's projected planar shadow (Blinn 1988, "Me and my (fake)
// shadow"): every caster triangle is flattened onto the receiver plane
// π = (n, d) from a light point L by the 4×4 matrix M = (π·L) I − L πᵀ, and
// the flattened triangles are drawn from the camera into the visibility
// target. A plane point X is shadowed iff the segment X→L meets a caster,
// iff X lies in some flattened triangle: an exact hard shadow, on the plane.
//
// planar_soft — the same from N stratified points on the area light
// (accumulation/light_samples.h), each darkening a pixel at most once by
// 1/N: the seeds' first soft-shadow method.
//
// What it does, and what it leaves out:
//  - Only pixels whose G-buffer point lies on the receiver plane
//    (|n·p + d| <= 1e-4 of the scene's radius) are shadowed; every other
//    pixel (the casters themselves, anything off the plane) counts as lit,
//    V = 1. The flattened geometry lies exactly in the plane, so the test is
//    made on the G-buffer position in the fragment shader, not by depth.
//  - Overlaps darken once: per light point the stencil marks every pixel
//    already darkened (reference = the sample's number, so it is cleared
//    once per 255 points, not per point).
//  - Anti-shadows: M maps a point P to w = π·L − π·P, its height below the
//    light along n. Parts of a caster at or above the light's height (w <= 0)
//    cannot shadow the plane; projected they would land on the far side of
//    infinity as a false "anti-shadow". They are clipped away explicitly by
//    gl_ClipDistance[0] = w: M is linear, so clipping the flattened triangle
//    in homogeneous space at w = 0 is clipping the caster at the light's
//    height, and what is left runs off towards infinity as it should
//    (w → 0⁺). (The camera's own homogeneous clipping already rejects the
//    w < 0 part on llvmpipe, whose clip coordinates are a negative multiple
//    of a point's; the clip distance does not rely on that.)
//  - A light point on or below the plane (π·L <= 0) lights nothing on the
//    plane's caster side: it darkens nothing (those points are in attached
//    shadow, which the harness applies).
//  - V is counted exactly: the target is cleared to N and each darkening
//    subtracts 1; planar_soft then divides by N in a last pass, keeping 0
//    and 1 exact. Alpha-tested casters are not honoured (need opaque_casters:
//    such scenes are skipped).
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <algorithm>
#include <memory>
#include <vector>

#include "accumulation/light_samples.h"
#include "core/error.h"
#include "gl/debug.h"
#include "gl/gpu_scene.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "planar/plateaus.h"
#include "planar/projected_shadow.h"
#include "plugin/registry.h"

namespace sb::techniques::planar {

using core::JobError;
using gl::DrawInfo;

namespace {

// Reads the count of unshadowed light points in the visibility target itself
// (after glTextureBarrier; each fragment reads only its own texel) and writes
// it back as a fraction, with 0 and N kept exact.
const char* const kResolveFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D count_tex;
uniform float samples;
out float visibility;
void main() {
  float seen = texelFetch(count_tex, ivec2(gl_FragCoord.xy), 0).r;
  visibility = seen >= samples ? 1.0 : seen / samples;
}
)";

class Planar final : public Technique {
 public:
  // points: (s, t) on the light; empty for the light's centre.
  Planar(std::string name, accumulation::LightSampleLayouts points)
      : name_(std::move(name)), points_(std::move(points)) {}

  void prepare(const FrameInputs& in) override {
    if (!in.has_receiver_plane) throw JobError(name_ + ": the scene has no planar receiver");
    // The scene's size, not the light's: the tolerance of the on-plane test.
    tolerance_ = 1e-4f * std::max(in.scene->bounds().radius(), 1e-6f);
    project_ = gl::Program(name_ + "_project", {kProjectVertex, "", kProjectFragment});
    if (points_.size() != 0)
      resolve_ =
          gl::Program(name_ + "_resolve", {gl::kFullscreenVertexShader, "", kResolveFragment});
    gl::throw_if_errors(name_ + " prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    const auto n = float(std::max<size_t>(points_.size(), 1));
    {
      auto pass = timer.scope("clear");
      glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
      glViewport(0, 0, in.width, in.height);
      const float count[4] = {n, n, n, n};
      glClearBufferfv(GL_COLOR, 0, count);
    }
    {
      auto pass = timer.scope("project");
      project(in);
    }
    if (points_.size() == 0) return;
    // The count of light points that see each pixel, as a fraction.
    auto pass = timer.scope("resolve");
    glTextureBarrier();
    resolve_.use();
    resolve_.set("samples", n);
    glBindTextureUnit(0, in.visibility_texture);
    gl::draw_fullscreen_triangle();
  }

 private:
  // Darkens each pixel once per light point whose flattened casters cover it.
  void project(const FrameInputs& in) const {
    glDisable(GL_DEPTH_TEST);  // the flattened casters lie in the plane: no depth test
    glDepthMask(GL_FALSE);
    glCullFace(GL_BACK);
    glEnable(GL_CLIP_DISTANCE0);
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);  // count − 1
    glBlendFunc(GL_ONE, GL_ONE);
    project_.use();
    project_.set("view_projection", in.view_projection);
    project_.set("receiver_plane", in.receiver_plane);
    project_.set("on_plane_tolerance", tolerance_);
    project_.set("darkening_value", 1.0f);  // subtracted from the count of light points
    glBindTextureUnit(0, in.gbuffer_position);
    const AreaLight& light = in.scene->light;
    const size_t count = std::max<size_t>(points_.size(), 1);
    for (size_t i = 0; i < count; ++i) {
      const glm::vec3 l = points_.size() == 0 ? light.center
                          : light.is_segment()
                              ? light.segment_end(points_.line[i])
                              : light.point(points_.square[i].x, points_.square[i].y);
      // The stencil holds the number (1..255) of the last point that darkened
      // the pixel: a pixel darkens once per point.
      const int ref = int(i % 255) + 1;
      if (ref == 1) {
        const GLint zero = 0;
        glClearBufferiv(GL_STENCIL, 0, &zero);
      }
      if (glm::dot(in.receiver_plane, glm::vec4(l, 1.0f)) <= 0.0f) continue;
      glStencilFunc(GL_NOTEQUAL, ref, 0xff);
      project_.set("shadow_projection", planar_projection(in.receiver_plane, l));
      in.gpu->draw_casters([](const DrawInfo& d) {
        // A closed caster's shadow is the flattened image of its light-facing
        // faces, which keep their winding seen from the plane's lit side,
        // where the camera is for every pixel the plane can shade: cull the
        // rest, half the fragments.
        if (d.cullable)
          glEnable(GL_CULL_FACE);
        else
          glDisable(GL_CULL_FACE);
      });
    }
    glDisable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_CLIP_DISTANCE0);
    glDepthMask(GL_TRUE);
  }

  std::string name_;
  accumulation::LightSampleLayouts points_;
  float tolerance_ = 0.0f;
  gl::Program project_;
  gl::Program resolve_;
};

}  // namespace
}  // namespace sb::techniques::planar

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  using namespace sb;
  using namespace sb::techniques::planar;
  registry.add(
      {.name = "planar",
       .family = "planar",
       .summary = "Blinn's projected shadow: casters flattened onto the receiver plane from the "
                  "light's centre; hard, on the plane only",
       .needs = Needs{need::kPlanarReceiver, need::kOpaqueCasters, need::kCasterClosedness},
       .params = {},
       .create = [](const Params&) {
         return std::make_unique<Planar>("planar", techniques::accumulation::LightSampleLayouts{});
       }});
  registry.add(
      {.name = "planar_soft",
       .family = "planar",
       .summary =
           "N projected planar shadows from stratified points on the area light, averaged; on the "
           "plane only",
       .needs = Needs{need::kPlanarReceiver, need::kOpaqueCasters, need::kCasterClosedness},
       .params =
           {int_param("samples", 64, 1, 65536,
                      "light points: an m×n grid of strata if N = m·n with n <= 2m, else the "
                      "Hammersley set"),
            bool_param(
                "jitter", true,
                "jitter each point inside its stratum (Hammersley: one random toroidal shift)"),
            int_param("seed", 1, 0, 2147483647, "jitter seed")},
       .create = [](const Params& p) {
         // Where the points lie on the light, in its own (s, t): parameters
         // only, so computed here; placed in the world per frame.
         return std::make_unique<Planar>(
             "planar_soft",
             techniques::accumulation::light_sample_layouts(
                 p.get_int("samples"), p.get_bool("jitter"), unsigned(p.get_int("seed"))));
       }});
  registry.add(plateaus_info());
}
