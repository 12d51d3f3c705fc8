// shadow_volume — stencil shadow volumes (Crow 1977; Heidmann 1991) from the
// light's centre, with silhouettes found per frame in a geometry shader from
// edge adjacency and extruded to infinity (w = 0) under GL_DEPTH_CLAMP.
//   z-pass: count volume faces in front of the G-buffer surface.
//   z-fail (Carmack's reverse): count faces behind it; needs both caps, and
//   works with the camera inside a volume.
// Hard shadows: V is 0 or 1. Needs closed 2-manifold casters and adjacency.
//
// Parameters, defaults and ranges: docs/parameters.md (generated from their
// declarations by `shadowbench list --markdown`).
#include <array>
#include <memory>

#include "core/error.h"
#include "gl/debug.h"
#include "gl/gpu_scene.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "plugin/registry.h"

namespace sb {
namespace {

const char* const kVolumeVertex = R"(#version 450 core
layout(location = 0) in vec3 position;
out vec3 v_world;
void main() { v_world = position; }
)";

// Input: a triangle with adjacency (0,2,4 = the triangle; 1,3,5 = the far
// vertices of its neighbours). Only light-facing triangles emit: a quad per
// silhouette edge (the neighbour faces away), plus both caps for z-fail.
const char* const kVolumeGeometry = R"(#version 450 core
layout(triangles_adjacency) in;
layout(triangle_strip, max_vertices = 18) out;
in vec3 v_world[];
uniform mat4 view_projection;
uniform vec3 light_position;
uniform bool caps;

bool faces_light(vec3 a, vec3 b, vec3 c) {
  return dot(cross(b - a, c - a), light_position - a) > 0.0;
}
void emit(vec3 p) { gl_Position = view_projection * vec4(p, 1.0); EmitVertex(); }
void emit_infinite(vec3 p) { gl_Position = view_projection * vec4(p - light_position, 0.0); EmitVertex(); }

void main() {
  vec3 p0 = v_world[0], p1 = v_world[2], p2 = v_world[4];
  if (!faces_light(p0, p1, p2)) return;
  vec3 tri[3] = vec3[3](p0, p1, p2);
  vec3 far_vertex[3] = vec3[3](v_world[1], v_world[3], v_world[5]);
  for (int e = 0; e < 3; ++e) {
    vec3 a = tri[e], b = tri[(e + 1) % 3];
    // A boundary edge repeats the triangle's own third vertex: never a silhouette
    // here (closed meshes only reach this shader).
    if (!faces_light(a, far_vertex[e], b)) {
      // Wound so that the quad faces outwards from the volume.
      emit(a); emit_infinite(a); emit(b); emit_infinite(b);
      EndPrimitive();
    }
  }
  if (caps) {
    emit(p0); emit(p1); emit(p2);
    EndPrimitive();
    emit_infinite(p0); emit_infinite(p2); emit_infinite(p1);
    EndPrimitive();
  }
}
)";

const char* const kResolveFragment = R"(#version 450 core
in vec2 uv;
layout(binding = 0) uniform sampler2D position_tex;
out float visibility;
void main() {
  // Drawn where the stencil count is non-zero: inside a volume, unless there
  // is no surface at all (background).
  vec4 pos = texelFetch(position_tex, ivec2(gl_FragCoord.xy), 0);
  visibility = pos.w == 0.0 ? 1.0 : 0.0;
}
)";

class ShadowVolume final : public Technique {
 public:
  explicit ShadowVolume(const Params& p)
      : zfail_(p.get_string("mode") == "zfail"), offset_(p.get_float("offset")) {}

  void prepare(const FrameInputs& in) override {
    // A scene without casters (a lone ground, inferred a receiver) has no
    // volumes to draw, and no adjacency: every point is lit.
    if (!in.gpu->has_adjacency() && in.scene->caster_triangle_count() > 0)
      throw JobError("shadow_volume: the scene has no adjacency");
    volume_ = gl::Program("shadow_volume", {kVolumeVertex, kVolumeGeometry, ""});
    resolve_ =
        gl::Program("shadow_volume_resolve", {gl::kFullscreenVertexShader, "", kResolveFragment});
    gl::throw_if_errors("shadow_volume prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glViewport(0, 0, in.width, in.height);
    {
      auto pass = timer.scope("volumes");
      glClearStencil(0);
      glClear(GL_STENCIL_BUFFER_BIT);
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LESS);
      glDepthMask(GL_FALSE);
      glEnable(GL_DEPTH_CLAMP);  // volumes reach infinity; don't clip them at the far plane
      glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
      glDisable(GL_CULL_FACE);
      glEnable(GL_STENCIL_TEST);
      glStencilFunc(GL_ALWAYS, 0, 0xff);
      glStencilMask(0xff);
      if (zfail_) {
        glStencilOpSeparate(GL_BACK, GL_KEEP, GL_INCR_WRAP, GL_KEEP);
        glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
      } else {
        glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_KEEP, GL_INCR_WRAP);
        glStencilOpSeparate(GL_BACK, GL_KEEP, GL_KEEP, GL_DECR_WRAP);
      }
      if (offset_ != 0.0f) {
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(0.0f, offset_);
      }
      volume_.use();
      volume_.set("view_projection", in.view_projection);
      volume_.set("light_position", in.scene->light.center);
      volume_.set("caps", zfail_ ? 1 : 0);
      if (in.gpu->has_adjacency()) in.gpu->draw_casters_adjacency();
      glDisable(GL_POLYGON_OFFSET_FILL);
      glDisable(GL_DEPTH_CLAMP);
    }
    auto pass = timer.scope("resolve");
    const std::array<float, 4> one{1.0f, 1.0f, 1.0f, 1.0f};
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearBufferfv(GL_COLOR, 0, one.data());
    glDisable(GL_DEPTH_TEST);
    glStencilFunc(GL_NOTEQUAL, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    resolve_.use();
    glBindTextureUnit(0, in.gbuffer_position);
    gl::draw_fullscreen_triangle();
    glDisable(GL_STENCIL_TEST);
    glDepthMask(GL_TRUE);
  }

 private:
  bool zfail_;
  float offset_;
  gl::Program volume_;
  gl::Program resolve_;
};

}  // namespace
}  // namespace sb

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  using namespace sb;
  registry.add({"shadow_volume",
                "shadow_volume",
                "stencil shadow volumes from the light's centre, silhouettes from adjacency "
                "(z-pass or z-fail with caps)",
                Needs{need::kClosedCasters, need::kEdgeAdjacency, need::kOpaqueCasters},
                {choice_param("mode", "zfail", {"zpass", "zfail"},
                              "zpass counts in front of the surface; zfail behind (robust)"),
                 float_param("offset", 1.0, -1e6, 1e6,
                             "glPolygonOffset units pushing volume faces away from the camera")},
                [](const Params& p) { return std::make_unique<ShadowVolume>(p); }});
}
