#pragma once
// The scene's geometry on the GPU: one vertex buffer (position at location 0,
// normal at location 1), one index buffer, one draw range per mesh, and — only
// when a technique in the plan asked for it — a GL_TRIANGLES_ADJACENCY index
// buffer of the casters.
#include <cstdint>
#include <vector>

#include "core/scene.h"
#include "gl/objects.h"

namespace sb {

class GpuScene {
 public:
  // adjacency: per mesh, indices from build_adjacency_indices(), or empty.
  GpuScene(const Scene& scene, const std::vector<std::vector<uint32_t>>& adjacency);

  const Scene& scene() const { return *scene_; }
  // Draws every mesh; `set_albedo(i)` is called before mesh i when given.
  void draw_all(GLint albedo_location = -1) const;
  void draw_casters() const;
  bool has_adjacency() const { return adjacency_count_ > 0; }
  // Casters as GL_TRIANGLES_ADJACENCY (6 indices per triangle).
  void draw_casters_adjacency() const;

 private:
  struct Range {
    GLsizei count;
    GLsizeiptr first_byte;
    GLint base_vertex;
    bool casts_shadow;
    glm::vec3 albedo;
  };
  const Scene* scene_;
  gl::Buffer vertices_;
  gl::Buffer indices_;
  gl::Buffer adjacency_;
  gl::VertexArray vao_;
  gl::VertexArray adjacency_vao_;
  std::vector<Range> ranges_;
  std::vector<Range> adjacency_ranges_;
  GLsizei adjacency_count_ = 0;
};

}  // namespace sb
