#include "gl/gpu_scene.h"

#include <stdexcept>

namespace sb {
namespace {

gl::VertexArray make_vao(GLuint vertices, GLuint indices) {
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  glVertexArrayVertexBuffer(vao, 0, vertices, 0, sizeof(float) * 6);
  glEnableVertexArrayAttrib(vao, 0);
  glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, 0, 0);
  glEnableVertexArrayAttrib(vao, 1);
  glVertexArrayAttribFormat(vao, 1, 3, GL_FLOAT, GL_FALSE, sizeof(float) * 3);
  glVertexArrayAttribBinding(vao, 1, 0);
  glVertexArrayElementBuffer(vao, indices);
  return gl::VertexArray(vao);
}

}  // namespace

GpuScene::GpuScene(const Scene& scene, const std::vector<std::vector<uint32_t>>& adjacency)
    : scene_(&scene) {
  std::vector<float> vertex_data;
  std::vector<uint32_t> index_data;
  std::vector<uint32_t> adjacency_data;
  GLint base = 0;
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const Mesh& m = scene.meshes[i];
    if (m.normals.size() != m.positions.size())
      throw std::logic_error("mesh '" + m.name + "' has no per-vertex normals");
    for (size_t v = 0; v < m.positions.size(); ++v) {
      const auto& p = m.positions[v];
      const auto& n = m.normals[v];
      vertex_data.insert(vertex_data.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
    }
    ranges_.push_back({GLsizei(m.indices.size()), GLsizeiptr(index_data.size() * 4), base,
                       m.casts_shadow, m.albedo});
    index_data.insert(index_data.end(), m.indices.begin(), m.indices.end());
    if (i < adjacency.size() && !adjacency[i].empty() && m.casts_shadow) {
      adjacency_ranges_.push_back({GLsizei(adjacency[i].size()),
                                   GLsizeiptr(adjacency_data.size() * 4), base, true, m.albedo});
      adjacency_data.insert(adjacency_data.end(), adjacency[i].begin(), adjacency[i].end());
    }
    base += GLint(m.positions.size());
  }
  vertices_ = gl::make_buffer(GLsizeiptr(vertex_data.size() * sizeof(float)), vertex_data.data());
  indices_ = gl::make_buffer(GLsizeiptr(index_data.size() * 4), index_data.data());
  vao_ = make_vao(vertices_.get(), indices_.get());
  if (!adjacency_data.empty()) {
    adjacency_ = gl::make_buffer(GLsizeiptr(adjacency_data.size() * 4), adjacency_data.data());
    adjacency_vao_ = make_vao(vertices_.get(), adjacency_.get());
    adjacency_count_ = GLsizei(adjacency_data.size());
  }
}

void GpuScene::draw_all(GLint albedo_location) const {
  glBindVertexArray(vao_.get());
  for (const auto& r : ranges_) {
    if (albedo_location >= 0) glUniform3f(albedo_location, r.albedo.x, r.albedo.y, r.albedo.z);
    glDrawElementsBaseVertex(GL_TRIANGLES, r.count, GL_UNSIGNED_INT,
                             reinterpret_cast<const void*>(r.first_byte), r.base_vertex);
  }
}

void GpuScene::draw_casters() const {
  glBindVertexArray(vao_.get());
  for (const auto& r : ranges_)
    if (r.casts_shadow)
      glDrawElementsBaseVertex(GL_TRIANGLES, r.count, GL_UNSIGNED_INT,
                               reinterpret_cast<const void*>(r.first_byte), r.base_vertex);
}

void GpuScene::draw_casters_adjacency() const {
  if (!has_adjacency()) throw std::logic_error("adjacency was not built for this scene");
  glBindVertexArray(adjacency_vao_.get());
  for (const auto& r : adjacency_ranges_)
    glDrawElementsBaseVertex(GL_TRIANGLES_ADJACENCY, r.count, GL_UNSIGNED_INT,
                             reinterpret_cast<const void*>(r.first_byte), r.base_vertex);
}

}  // namespace sb
