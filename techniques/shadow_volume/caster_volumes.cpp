#include "shadow_volume/caster_volumes.h"

#include <array>
#include <stdexcept>
#include <utility>

#include "gl/debug.h"
#include "plugin/need_data.h"
#include "shadow_volume/near_plane_pyramid.h"

namespace sb::techniques::shadow_volume {

using core::choice_param;
using core::float_param;
using core::Mesh;
using core::Params;
using core::ParamSpec;
using plugin::CasterEdges;
using plugin::FrameInputs;

const char* const kVolumeVertex = R"(#version 450 core
layout(location = 0) in vec4 position;
uniform mat4 view_projection;
void main() { gl_Position = view_projection * position; }
)";

const char* const kStencilResolveFragment = R"(#version 450 core
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

std::vector<ParamSpec> silhouette_params(const std::string& silhouette_help) {
  return {
      choice_param("silhouette", "discrete", {"discrete", "accurate", "smooth"}, silhouette_help),
      float_param("epsilon", 0.01, 1e-6, 1e6,
                  "smooth: subdivide until the curve is within this of its chords (world "
                  "units)"),
      float_param("smooth_offset", 0.0, 0.0, 1e6,
                  "smooth: move the silhouette this far along the negative normal (world "
                  "units) against light leaks")};
}

SilhouetteSettings silhouette_settings(const Params& p) {
  SilhouetteSettings s;
  s.mode = silhouette_mode_from_string(p.get_string("silhouette"));
  s.epsilon = p.get_float("epsilon");
  s.offset = p.get_float("smooth_offset");
  return s;
}

CountMode count_mode_from_string(const std::string& s) {
  if (s == "zpass") return CountMode::ZPass;
  if (s == "zfail") return CountMode::ZFail;
  if (s == "auto") return CountMode::Auto;
  throw std::invalid_argument("unknown volume count mode '" + s + "'");
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

void begin_stencil_count(float offset) {
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
  if (offset != 0.0f) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(0.0f, offset);
  }
}

void end_stencil_count() {
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_DEPTH_CLAMP);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void resolve_stencil(const FrameInputs& in, const gl::Program& resolve) {
  const std::array<float, 4> one{1.0f, 1.0f, 1.0f, 1.0f};
  glClearBufferfv(GL_COLOR, 0, one.data());
  glDisable(GL_DEPTH_TEST);
  glStencilFunc(GL_NOTEQUAL, 0, 0xff);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  resolve.use();
  glBindTextureUnit(0, in.gbuffer_position);
  gl::draw_fullscreen_triangle();
  glDisable(GL_STENCIL_TEST);
  glDepthMask(GL_TRUE);
}

void make_vec4_stream(gl::Buffer& buffer, gl::VertexArray& vao) {
  buffer = gl::make_stream_buffer();
  const GLuint b = buffer.get();
  GLuint v = 0;
  glCreateVertexArrays(1, &v);
  vao = gl::VertexArray(v);
  glVertexArrayVertexBuffer(v, 0, b, 0, sizeof(glm::vec4));
  glEnableVertexArrayAttrib(v, 0);
  glVertexArrayAttribFormat(v, 0, 4, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(v, 0, 0);
}

void CasterVolumes::prepare(const FrameInputs& in) {
  casters_.clear();
  const auto* edges = cpu_ ? &in.derived->get<CasterEdges>(plugin::need::kCasterEdges) : nullptr;
  for (size_t i = 0; i < in.scene->meshes.size(); ++i) {
    const Mesh& m = in.scene->meshes[i];
    if (!m.casts_shadow || m.indices.empty()) continue;
    Caster c;
    c.mesh = i;
    for (uint32_t v : m.indices) c.box.extend(m.positions[v]);
    if (cpu_) c.shape = make_silhouette_mesh(m, (*edges)[i]);
    casters_.push_back(std::move(c));
  }
  if (!cpu_) return;
  program_ = gl::Program("caster_volumes", {kVolumeVertex, "", ""});
  make_vec4_stream(vertices_, vao_);
  gl::throw_if_errors("caster volumes prepare");
}

void CasterVolumes::choose_zfail(const FrameInputs& in) {
  if (mode_ != CountMode::Auto) {
    for (Caster& c : casters_) c.zfail = mode_ == CountMode::ZFail;
    return;
  }
  const NearPlanePyramid pyramid(in.scene->light.center, in.view_projection);
  for (Caster& c : casters_) c.zfail = pyramid.may_intersect(c.box);
}

void CasterVolumes::find_silhouettes(const glm::vec3& light) {
  silhouettes_.resize(casters_.size());
  for (size_t i = 0; i < casters_.size(); ++i)
    extract_silhouette(casters_[i].shape, light, settings_, silhouettes_[i]);
}

void CasterVolumes::extrude(const glm::vec3& light) {
  mesh_.clear();
  for (size_t i = 0; i < casters_.size(); ++i)
    casters_[i].range = append_volume(silhouettes_[i], light, casters_[i].zfail, mesh_);
}

void CasterVolumes::upload() {
  // Orphaned and refilled every frame, as a dynamic vertex stream.
  gl::set_buffer_data(vertices_, GLsizeiptr(mesh_.vertices.size() * sizeof(glm::vec4)),
                      mesh_.vertices.data(), GL_STREAM_DRAW);
}

void CasterVolumes::draw(const FrameInputs& in, bool zfail) {
  firsts_.clear();
  counts_.clear();
  for (const Caster& c : casters_)
    if (c.zfail == zfail && c.range.sides + c.range.caps > 0) {
      firsts_.push_back(c.range.first);
      counts_.push_back(zfail ? c.range.sides + c.range.caps : c.range.sides);
    }
  if (firsts_.empty()) return;
  program_.use();
  program_.set("view_projection", in.view_projection);
  glBindVertexArray(vao_.get());
  glMultiDrawArrays(GL_TRIANGLES, firsts_.data(), counts_.data(), GLsizei(firsts_.size()));
}

void CasterVolumes::draw_caster(const FrameInputs& in, size_t caster, const gl::Program* program) {
  const Caster& c = casters_[caster];
  if (c.range.sides + c.range.caps == 0) return;
  set_stencil_ops(c.zfail);
  if (program != nullptr) {
    program->use();
  } else {
    program_.use();
    program_.set("view_projection", in.view_projection);
  }
  glBindVertexArray(vao_.get());
  glDrawArrays(GL_TRIANGLES, c.range.first, c.zfail ? c.range.sides + c.range.caps : c.range.sides);
}

}  // namespace sb::techniques::shadow_volume
