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
#include "plugin/need_data.h"
#include "plugin/registry.h"
#include "shadow_volume/near_plane_pyramid.h"
#include "shadow_volume/silhouette.h"
#include "shadow_volume/volume_mesh.h"

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

// The CPU path's volumes: homogeneous positions, w = 0 at infinity.
const char* const kCpuVolumeVertex = R"(#version 450 core
layout(location = 0) in vec4 position;
uniform mat4 view_projection;
void main() { gl_Position = view_projection * position; }
)";

enum class Mode { ZPass, ZFail, Auto };
Mode mode_from_string(const std::string& s) {
  if (s == "zpass") return Mode::ZPass;
  if (s == "zfail") return Mode::ZFail;
  return Mode::Auto;
}

void set_stencil_ops(bool zfail) {
  if (zfail) {
    glStencilOpSeparate(GL_BACK, GL_KEEP, GL_INCR_WRAP, GL_KEEP);
    glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
  } else {
    glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_KEEP, GL_INCR_WRAP);
    glStencilOpSeparate(GL_BACK, GL_KEEP, GL_KEEP, GL_DECR_WRAP);
  }
}

class ShadowVolume final : public Technique {
 public:
  explicit ShadowVolume(const Params& p)
      : mode_(mode_from_string(p.get_string("mode"))),
        offset_(p.get_float("offset")),
        cpu_(p.get_string("silhouettes") == "cpu") {
    settings_.mode = volume::silhouette_mode_from_string(p.get_string("silhouette"));
    settings_.epsilon = p.get_float("epsilon");
    settings_.offset = p.get_float("smooth_offset");
  }

  void prepare(const FrameInputs& in) override {
    // A scene without casters (a lone ground, inferred a receiver) has no
    // volumes to draw, and no adjacency: every point is lit.
    if (!cpu_ && !in.gpu->has_adjacency() && in.scene->caster_triangle_count() > 0)
      throw JobError("shadow_volume: the scene has no adjacency");
    // Scene data only: each caster's box (for `auto`) and, on the CPU path,
    // its triangles and edges.
    casters_.clear();
    const auto* edges = cpu_ ? &in.derived->get<CasterEdges>(need::kCasterEdges) : nullptr;
    for (size_t i = 0; i < in.scene->meshes.size(); ++i) {
      const Mesh& m = in.scene->meshes[i];
      if (!m.casts_shadow || m.indices.empty()) continue;
      Caster c;
      c.mesh = i;
      for (uint32_t v : m.indices) c.box.extend(m.positions[v]);
      if (cpu_) c.shape = volume::make_silhouette_mesh(m, (*edges)[i]);
      casters_.push_back(std::move(c));
    }
    if (cpu_) {
      volume_ = gl::Program("shadow_volume_cpu", {kCpuVolumeVertex, "", ""});
      GLuint buffer = 0, vao = 0;
      glCreateBuffers(1, &buffer);
      vertices_ = gl::Buffer(buffer);
      glCreateVertexArrays(1, &vao);
      vao_ = gl::VertexArray(vao);
      glVertexArrayVertexBuffer(vao, 0, buffer, 0, sizeof(glm::vec4));
      glEnableVertexArrayAttrib(vao, 0);
      glVertexArrayAttribFormat(vao, 0, 4, GL_FLOAT, GL_FALSE, 0);
      glVertexArrayAttribBinding(vao, 0, 0);
    } else {
      volume_ = gl::Program("shadow_volume", {kVolumeVertex, kVolumeGeometry, ""});
    }
    resolve_ =
        gl::Program("shadow_volume_resolve", {gl::kFullscreenVertexShader, "", kResolveFragment});
    gl::throw_if_errors("shadow_volume prepare");
  }

  void render(const FrameInputs& in, gl::PassTimer& timer) override {
    const glm::vec3 light = in.scene->light.center;
    if (cpu_) {
      auto pass = timer.scope("silhouettes");
      choose_zfail(in);
      silhouettes_.resize(casters_.size());
      for (size_t i = 0; i < casters_.size(); ++i)
        volume::extract_silhouette(casters_[i].shape, light, settings_, silhouettes_[i]);
    }
    if (cpu_) {
      auto pass = timer.scope("extrusion");
      mesh_.clear();
      for (size_t i = 0; i < casters_.size(); ++i)
        casters_[i].range = volume::append_volume(silhouettes_[i], light, casters_[i].zfail, mesh_);
    }
    if (cpu_) {
      auto pass = timer.scope("upload");
      // Orphaned and refilled every frame, as a dynamic vertex stream.
      glNamedBufferData(vertices_.get(), GLsizeiptr(mesh_.vertices.size() * sizeof(glm::vec4)),
                        mesh_.vertices.data(), GL_STREAM_DRAW);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, in.visibility_framebuffer);
    glViewport(0, 0, in.width, in.height);
    {
      auto pass = timer.scope("stencil");
      if (!cpu_) choose_zfail(in);
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
      if (offset_ != 0.0f) {
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(0.0f, offset_);
      }
      volume_.use();
      volume_.set("view_projection", in.view_projection);
      for (const bool zfail : {false, true}) {
        set_stencil_ops(zfail);
        if (cpu_)
          draw_cpu_volumes(zfail);
        else
          draw_gpu_volumes(in, zfail);
      }
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
  struct Caster {
    size_t mesh = 0;  // index into Scene::meshes
    Bounds box;
    volume::SilhouetteMesh shape;  // CPU path only
    bool zfail = true;
    volume::VolumeVertices::Range range;
  };

  // Per caster, this frame: z-fail or z-pass (the camera and light may move).
  void choose_zfail(const FrameInputs& in) {
    if (mode_ != Mode::Auto) {
      for (Caster& c : casters_) c.zfail = mode_ == Mode::ZFail;
      return;
    }
    const volume::NearPlanePyramid pyramid(in.scene->light.center, in.view_projection);
    for (Caster& c : casters_) c.zfail = pyramid.may_intersect(c.box);
  }

  void draw_cpu_volumes(bool zfail) {
    firsts_.clear();
    counts_.clear();
    for (const Caster& c : casters_)
      if (c.zfail == zfail && c.range.sides + c.range.caps > 0) {
        firsts_.push_back(c.range.first);
        counts_.push_back(zfail ? c.range.sides + c.range.caps : c.range.sides);
      }
    if (firsts_.empty()) return;
    glBindVertexArray(vao_.get());
    glMultiDrawArrays(GL_TRIANGLES, firsts_.data(), counts_.data(), GLsizei(firsts_.size()));
  }

  void draw_gpu_volumes(const FrameInputs& in, bool zfail) {
    if (!in.gpu->has_adjacency()) return;
    include_.assign(in.scene->meshes.size(), false);
    bool any = false;
    for (const Caster& c : casters_)
      if (c.zfail == zfail) include_[c.mesh] = true, any = true;
    if (!any) return;
    volume_.set("light_position", in.scene->light.center);
    volume_.set("caps", zfail ? 1 : 0);
    in.gpu->draw_casters_adjacency([this](size_t mesh) { return bool(include_[mesh]); });
  }

  Mode mode_;
  float offset_;
  bool cpu_;
  volume::SilhouetteSettings settings_;
  std::vector<Caster> casters_;
  std::vector<volume::Silhouette> silhouettes_;
  volume::VolumeVertices mesh_;
  std::vector<GLint> firsts_;
  std::vector<GLsizei> counts_;
  std::vector<char> include_;
  gl::Program volume_;
  gl::Program resolve_;
  gl::Buffer vertices_;
  gl::VertexArray vao_;
};

}  // namespace
}  // namespace sb

SHADOWBENCH_PLUGIN_ENTRY(sb::Registry& registry) {
  using namespace sb;
  TechniqueInfo info{
      "shadow_volume",
      "shadow_volume",
      "stencil shadow volumes from the light's centre (z-pass, z-fail with caps, or auto per "
      "caster); discrete silhouettes in a geometry shader, or discrete, accurate or smooth "
      "silhouettes (Mattausch et al. 2012) on the CPU",
      Needs{need::kClosedCasters, need::kEdgeAdjacency, need::kOpaqueCasters, need::kCasterEdges},
      {choice_param("mode", "zfail", {"zpass", "zfail", "auto"},
                    "zpass counts in front of the surface; zfail behind (robust); auto uses zfail "
                    "only for casters whose volume can reach the camera's near plane"),
       float_param("offset", 1.0, -1e6, 1e6,
                   "glPolygonOffset units pushing volume faces away from the camera"),
       choice_param("silhouettes", "gpu", {"gpu", "cpu"},
                    "where silhouettes are found and extruded: a geometry shader, or the CPU "
                    "with the volume uploaded every frame"),
       choice_param("silhouette", "discrete", {"discrete", "accurate", "smooth"},
                    "discrete: edges between lit and unlit faces; accurate: where the vertex "
                    "normals' n·(l−v) crosses zero; smooth: accurate lifted onto the curved "
                    "surface and subdivided (cpu only)"),
       float_param("epsilon", 0.01, 1e-6, 1e6,
                   "smooth: subdivide until the curve is within this of its chords (world units)"),
       float_param("smooth_offset", 0.0, 0.0, 1e6,
                   "smooth: move the silhouette this far along the negative normal (world units) "
                   "against light leaks")},
      [](const Params& p) { return std::make_unique<ShadowVolume>(p); }};
  info.check = [](const Params& p) -> std::pair<std::string, std::string> {
    if (p.get_string("silhouettes") == "gpu" && p.get_string("silhouette") != "discrete")
      return {"silhouette",
              "'" + p.get_string("silhouette") +
                  "' silhouettes are found on the CPU only; set silhouettes to \"cpu\""};
    return {};
  };
  registry.add(std::move(info));
}
