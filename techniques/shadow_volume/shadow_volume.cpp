// shadow_volume — stencil shadow volumes (Crow 1977; Heidmann 1991) from the
// light's centre, extruded to infinity (w = 0) under GL_DEPTH_CLAMP.
//   z-pass: count volume faces in front of the G-buffer surface.
//   z-fail (Carmack's reverse): count faces behind it; needs both caps, and
//   works with the camera inside a volume.
//   auto: z-fail for the casters whose volume can reach the camera's
//   near-plane rectangle (near_plane_pyramid.h), z-pass for the rest.
// Silhouettes are found per frame, either in a geometry shader from edge
// adjacency (`silhouettes: gpu`, discrete only), or on the CPU from the edge
// list with the extruded triangles uploaded every frame (`silhouettes: cpu`),
// as engines did before geometry shaders. The CPU path also finds the
// accurate and smooth silhouettes of Mattausch et al. 2012 (silhouette.h).
// Passes: silhouettes (CPU extraction), extrusion (CPU triangles), upload,
// stencil (on the GPU path also the shader's extraction and extrusion),
// resolve.
// Hard shadows: V is 0 or 1. Needs closed 2-manifold casters.
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
#include "gl/gpu_scene.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "plugin/registry.h"
#include "shadow_volume/caster_volumes.h"
#include "shadow_volume/hybrid_reconstruction.h"

namespace sb::techniques::shadow_volume {

using core::JobError;

namespace {

const char* const kWorldVertex = R"(#version 450 core
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

class ShadowVolume final : public Technique {
 public:
  explicit ShadowVolume(const Params& p)
      : offset_(p.get_float("offset")),
        cpu_(p.get_string("silhouettes") == "cpu"),
        volumes_(count_mode_from_string(p.get_string("mode")), cpu_, silhouette_settings(p)) {}

  void prepare(const FrameInputs& in) override {
    // A scene without casters (a lone ground, inferred a receiver) has no
    // volumes to draw, and no adjacency: every point is lit.
    if (!cpu_ && !in.gpu->has_adjacency() && in.scene->caster_triangle_count() > 0)
      throw JobError("shadow_volume: the scene has no adjacency");
    volumes_.prepare(in);
    if (!cpu_) volume_ = gl::Program("shadow_volume", {kWorldVertex, kVolumeGeometry, ""});
    resolve_ = gl::Program("shadow_volume_resolve",
                           {gl::kFullscreenVertexShader, "", kStencilResolveFragment});
    gl::throw_if_errors("shadow_volume prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    const glm::vec3 light = in.scene->light.center;
    if (cpu_) {
      auto pass = timer.scope("silhouettes");
      volumes_.choose_zfail(in);
      volumes_.find_silhouettes(light);
    }
    if (cpu_) {
      auto pass = timer.scope("extrusion");
      volumes_.extrude(light);
    }
    if (cpu_) {
      auto pass = timer.scope("upload");
      volumes_.upload();
    }
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glViewport(0, 0, in.width, in.height);
    {
      auto pass = timer.scope("stencil");
      if (!cpu_) volumes_.choose_zfail(in);
      begin_stencil_count(offset_);
      for (const bool zfail : {false, true}) {
        set_stencil_ops(zfail);
        if (cpu_)
          volumes_.draw(in, zfail);
        else
          draw_gpu_volumes(in, zfail);
      }
      end_stencil_count();
    }
    auto pass = timer.scope("resolve");
    resolve_stencil(in, resolve_);
  }

 private:
  void draw_gpu_volumes(const FrameInputs& in, bool zfail) {
    if (!in.gpu->has_adjacency()) return;
    include_.assign(in.scene->meshes.size(), false);
    bool any = false;
    for (const auto& c : volumes_.casters())
      if (c.zfail == zfail) include_[c.mesh] = true, any = true;
    if (!any) return;
    volume_.use();
    volume_.set("view_projection", in.view_projection);
    volume_.set("light_position", in.scene->light.center);
    volume_.set("caps", zfail ? 1 : 0);
    in.gpu->draw_casters_adjacency([this](size_t mesh) { return bool(include_[mesh]); });
  }

  float offset_;
  bool cpu_;
  CasterVolumes volumes_;
  std::vector<char> include_;
  gl::Program volume_;
  gl::Program resolve_;
};

}  // namespace
}  // namespace sb::techniques::shadow_volume

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  using namespace sb;
  using namespace sb::techniques::shadow_volume;
  std::vector<ParamSpec> params = {
      choice_param("mode", "zfail", {"zpass", "zfail", "auto"},
                   "zpass counts in front of the surface; zfail behind (robust); auto uses zfail "
                   "only for casters whose volume can reach the camera's near plane"),
      float_param("offset", 1.0, -1e6, 1e6,
                  "glPolygonOffset units pushing volume faces away from the camera"),
      choice_param("silhouettes", "gpu", {"gpu", "cpu"},
                   "where silhouettes are found and extruded: a geometry shader, or the CPU "
                   "with the volume uploaded every frame")};
  for (ParamSpec& spec : silhouette_params(
           "discrete: edges between lit and unlit faces; accurate: where the vertex normals' "
           "n·(l−v) crosses zero; smooth: accurate lifted onto the curved surface and subdivided "
           "(cpu only)"))
    params.push_back(std::move(spec));
  registry.add(
      {.name = "shadow_volume",
       .family = "shadow_volume",
       .summary =
           "stencil shadow volumes from the light's centre (z-pass, z-fail with caps, or auto per "
           "caster); discrete silhouettes in a geometry shader, or discrete, accurate or smooth "
           "silhouettes (Mattausch et al. 2012) on the CPU",
       .needs = Needs{need::kClosedCasters, need::kEdgeAdjacency, need::kOpaqueCasters,
                      need::kCasterEdges},
       .params = std::move(params),
       .create = [](const Params& p) { return std::make_unique<ShadowVolume>(p); },
       .check = [](const Params& p) -> std::pair<std::string, std::string> {
         if (p.get_string("silhouettes") == "gpu" && p.get_string("silhouette") != "discrete")
           return {"silhouette",
                   "'" + p.get_string("silhouette") +
                       "' silhouettes are found on the CPU only; set silhouettes to \"cpu\""};
         return {};
       }});
  registry.add(hybrid_reconstruction_info());
}
