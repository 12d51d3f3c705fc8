#include "gl/gpu_scene.h"

#include <stdexcept>

#include "gl/allocation_meter.h"

namespace sb::gl {

using core::Mesh;
using core::Scene;
using core::TextureImage;

namespace {

constexpr GLsizei kStride = sizeof(float) * 8;  // position, normal, uv

gl::VertexArray make_vao(GLuint vertices, GLuint indices) {
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  glVertexArrayVertexBuffer(vao, 0, vertices, 0, kStride);
  const GLint sizes[3] = {3, 3, 2};
  GLuint offset = 0;
  for (GLuint a = 0; a < 3; ++a) {
    glEnableVertexArrayAttrib(vao, a);
    glVertexArrayAttribFormat(vao, a, sizes[a], GL_FLOAT, GL_FALSE, offset);
    glVertexArrayAttribBinding(vao, a, 0);
    offset += GLuint(sizes[a]) * GLuint(sizeof(float));
  }
  glVertexArrayElementBuffer(vao, indices);
  return gl::VertexArray(vao);
}

gl::Texture upload(const TextureImage& t) {
  gl::Texture tex = gl::make_texture_2d(GL_RGBA8, t.width, t.height);
  // Nearest and repeat: the same texel the ray tracer's sample_alpha reads.
  glTextureParameteri(tex.get(), GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(tex.get(), GL_TEXTURE_WRAP_T, GL_REPEAT);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // Row 0 of the image is v = 0, which is GL's first row: no flip.
  glTextureSubImage2D(tex.get(), 0, 0, 0, t.width, t.height, GL_RGBA, GL_UNSIGNED_BYTE,
                      t.rgba.data());
  return tex;
}

}  // namespace

GpuScene::GpuScene(const Scene& scene, const std::vector<std::vector<uint32_t>>& adjacency,
                   const std::vector<MeshDrawFlags>& flags)
    : scene_(&scene) {
  for (const auto& t : scene.textures) textures_.push_back(upload(t));
  std::vector<float> vertex_data;
  std::vector<uint32_t> index_data;
  std::vector<uint32_t> adjacency_data;
  GLint base = 0;
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const Mesh& m = scene.meshes[i];
    if (m.normals.size() != m.positions.size())
      throw std::logic_error("mesh '" + m.name + "' has no per-vertex normals");
    const bool has_uv = m.uvs.size() == m.positions.size();
    for (size_t v = 0; v < m.positions.size(); ++v) {
      const auto& p = m.positions[v];
      const auto& n = m.normals[v];
      const glm::vec2 uv = has_uv ? m.uvs[v] : glm::vec2(0.0f);
      vertex_data.insert(vertex_data.end(), {p.x, p.y, p.z, n.x, n.y, n.z, uv.x, uv.y});
    }
    DrawInfo info;
    info.albedo = m.albedo;
    if (m.base_color_texture >= 0 && size_t(m.base_color_texture) < textures_.size() && has_uv)
      info.texture = textures_[size_t(m.base_color_texture)].get();
    info.alpha_tested = m.alpha_tested() && info.texture != 0;
    info.alpha_cutoff = m.alpha_cutoff;
    info.double_sided = m.double_sided;
    info.casts_shadow = m.casts_shadow;
    if (i < flags.size()) {
      info.cullable = m.casts_shadow && flags[i].closed;
      info.in_receiver_maps = !m.casts_shadow && flags[i].nothing_behind;
    }
    // Indices are stored with the mesh's base vertex added (base_vertex 0),
    // so that neighbours drawn alike can share one draw (batches_).
    ranges_.push_back(
        {GLsizei(m.indices.size()), GLsizeiptr(index_data.size() * 4), 0, m.casts_shadow, info, i});
    for (uint32_t k : m.indices) index_data.push_back(k + uint32_t(base));
    if (i < adjacency.size() && !adjacency[i].empty() && m.casts_shadow) {
      adjacency_ranges_.push_back({GLsizei(adjacency[i].size()),
                                   GLsizeiptr(adjacency_data.size() * 4), base, true, info, i});
      adjacency_data.insert(adjacency_data.end(), adjacency[i].begin(), adjacency[i].end());
    }
    base += GLint(m.positions.size());
  }
  // No cap on a run's length: llvmpipe's rasteriser threads, not its draw
  // module, take a big draw's time; capping a 2.8 M-triangle draw at 65,536
  // or 1 M triangles made no frame faster (docs/performance.md, "Heavy
  // instancing").
  for (const Range& r : ranges_) {
    if (!batches_.empty() && batches_.back().info == r.info &&
        batches_.back().first_byte + GLsizeiptr(batches_.back().count) * 4 == r.first_byte)
      batches_.back().count += r.count;
    else
      batches_.push_back(r);
  }
  vertices_ = gl::make_buffer(GLsizeiptr(vertex_data.size() * sizeof(float)), vertex_data.data());
  indices_ = gl::make_buffer(GLsizeiptr(index_data.size() * 4), index_data.data());
  vao_ = make_vao(vertices_.get(), indices_.get());
  if (!adjacency_data.empty()) {
    // Held for the techniques that declare need::kEdgeAdjacency, which are
    // charged it (gl/allocation_meter.h).
    const AllocationWindow window;
    adjacency_ = gl::make_buffer(GLsizeiptr(adjacency_data.size() * 4), adjacency_data.data());
    adjacency_vao_ = make_vao(vertices_.get(), adjacency_.get());
    adjacency_count_ = GLsizei(adjacency_data.size());
    adjacency_bytes_ = window.live_bytes();
  }
}

std::vector<GpuScene::MeshRange> GpuScene::mesh_ranges() const {
  std::vector<MeshRange> out;
  for (const auto& r : ranges_)
    out.push_back({r.count, r.first_byte, r.base_vertex, r.casts_shadow});
  return out;
}

bool GpuScene::has_alpha_tested_casters() const {
  for (const auto& r : ranges_)
    if (r.casts_shadow && r.info.alpha_tested) return true;
  return false;
}

void GpuScene::draw(const Range& r, GLenum mode) const {
  glDrawElementsBaseVertex(mode, r.count, GL_UNSIGNED_INT,
                           reinterpret_cast<const void*>(r.first_byte), r.base_vertex);
}

void GpuScene::draw_all(const std::function<void(const DrawInfo&)>& setup) const {
  glBindVertexArray(vao_.get());
  for (const auto& r : batches_) {
    setup(r.info);
    draw(r, GL_TRIANGLES);
  }
}

void GpuScene::draw_casters_and_map_receivers(
    const std::function<void(const DrawInfo&)>& setup) const {
  glBindVertexArray(vao_.get());
  for (const auto& r : batches_)
    if (r.casts_shadow || r.info.in_receiver_maps) {
      setup(r.info);
      draw(r, GL_TRIANGLES);
    }
}

void GpuScene::draw_casters(const std::function<void(const DrawInfo&)>& setup) const {
  glBindVertexArray(vao_.get());
  for (const auto& r : batches_)
    if (r.casts_shadow) {
      setup(r.info);
      draw(r, GL_TRIANGLES);
    }
}

void GpuScene::draw_casters() const {
  glBindVertexArray(vao_.get());
  for (const auto& r : batches_)
    if (r.casts_shadow) draw(r, GL_TRIANGLES);
}

void GpuScene::draw_casters_adjacency() const {
  if (!has_adjacency()) throw std::logic_error("adjacency was not built for this scene");
  glBindVertexArray(adjacency_vao_.get());
  for (const auto& r : adjacency_ranges_) draw(r, GL_TRIANGLES_ADJACENCY);
}

void GpuScene::draw_casters_adjacency(const std::function<bool(size_t mesh)>& include) const {
  if (!has_adjacency()) throw std::logic_error("adjacency was not built for this scene");
  glBindVertexArray(adjacency_vao_.get());
  for (const auto& r : adjacency_ranges_)
    if (include(r.mesh)) draw(r, GL_TRIANGLES_ADJACENCY);
}

const char* const kSceneVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec2 uv;
uniform mat4 view_projection;
out vec3 v_world;
out vec3 v_normal;
out vec2 v_uv;
void main() {
  v_world = position;
  v_normal = normal;
  v_uv = uv;
  gl_Position = view_projection * vec4(position, 1.0);
}
)";

}  // namespace sb::gl
