#pragma once
// The scene's geometry on the GPU: one vertex buffer (position at location 0,
// normal at 1, texture coordinate at 2), one index buffer, one draw range per
// mesh (consecutive meshes drawn alike are drawn together), the scene's
// textures, and — only when a technique in the plan asked for it — a
// GL_TRIANGLES_ADJACENCY index buffer of the casters.
#include <cstdint>
#include <functional>
#include <vector>

#include "core/scene.h"
#include "gl/objects.h"

namespace sb::gl {

// What a pass needs to know about one mesh before drawing it.
struct DrawInfo {
  glm::vec3 albedo{0.8f};
  GLuint texture = 0;  // base colour (rgb × albedo, a = coverage), 0 if none
  bool alpha_tested = false;
  float alpha_cutoff = 0.5f;
  bool double_sided = false;
  bool casts_shadow = true;
  // A closed caster: a depth pass may cull its front or back faces. Culling
  // an open one (a roof quad) would drop the faces that make its shadow.
  bool cullable = false;
  // A receiver with nothing behind it from the light: filtered maps may draw
  // it to give their filters a floor (filtered_map.h). Any other receiver in
  // a map would occlude what lies behind it, which it does not.
  bool in_receiver_maps = false;
  // Meshes whose DrawInfo is equal draw alike: neighbours share one draw.
  bool operator==(const DrawInfo&) const = default;
};

// What the plan derived about each mesh; empty: nothing culled, no receiver
// in maps.
struct MeshDrawFlags {
  bool closed = false;
  bool nothing_behind = false;
};

class GpuScene {
 public:
  // adjacency: per mesh, indices from build_adjacency_indices(), or empty.
  GpuScene(const core::Scene& scene, const std::vector<std::vector<uint32_t>>& adjacency,
           const std::vector<MeshDrawFlags>& flags = {});

  const core::Scene& scene() const { return *scene_; }
  bool has_alpha_tested_casters() const;
  // Draws every mesh (draw_all) or the casters (draw_casters); `setup` runs
  // before each mesh so the pass can switch programs, uniforms or culling.
  void draw_all(const std::function<void(const DrawInfo&)>& setup) const;
  void draw_casters(const std::function<void(const DrawInfo&)>& setup) const;
  // The casters and the receivers marked in_receiver_maps.
  void draw_casters_and_map_receivers(const std::function<void(const DrawInfo&)>& setup) const;
  // Casters only, ignoring materials (for passes that cannot honour masks).
  void draw_casters() const;
  bool has_adjacency() const { return adjacency_count_ > 0; }
  // Casters as GL_TRIANGLES_ADJACENCY (6 indices per triangle).
  void draw_casters_adjacency() const;
  // Only the casters whose scene mesh index `include` accepts.
  void draw_casters_adjacency(const std::function<bool(size_t mesh)>& include) const;

  // Read-only views for techniques that read the scene in their own shaders
  // (bind as GL_SHADER_STORAGE_BUFFER; never write them) instead of
  // uploading it again. Vertices are kFloatsPerVertex floats: position,
  // normal, texture coordinate; indices are uint32 triangle lists.
  static constexpr int kFloatsPerVertex = 8;
  struct MeshRange {
    GLsizei index_count;
    GLsizeiptr first_index_byte;  // into index_buffer()
    GLint base_vertex;            // added to every index of the mesh
    bool casts_shadow;
  };
  GLuint vertex_buffer() const { return vertices_.get(); }
  GLuint index_buffer() const { return indices_.get(); }
  GLuint adjacency_buffer() const { return adjacency_.get(); }  // 0 unless built
  // The adjacency buffer's storage as the meter counts it (gl/allocation_meter.h:
  // 4 bytes an index, 6 indices a caster triangle); 0 unless built.
  std::int64_t adjacency_bytes() const { return adjacency_bytes_; }
  std::vector<MeshRange> mesh_ranges() const;

 private:
  struct Range {
    GLsizei count;
    GLsizeiptr first_byte;
    GLint base_vertex;
    bool casts_shadow;
    DrawInfo info;
    size_t mesh = 0;  // index into Scene::meshes
  };
  void draw(const Range& r, GLenum mode) const;
  const core::Scene* scene_;
  gl::Buffer vertices_;
  gl::Buffer indices_;
  gl::Buffer adjacency_;
  gl::VertexArray vao_;
  gl::VertexArray adjacency_vao_;
  std::vector<gl::Texture> textures_;
  std::vector<Range> ranges_;
  // Runs of consecutive meshes drawn alike, one draw each: a glTF placing
  // one mesh 200,000 times would otherwise cost 200,000 draws a pass.
  std::vector<Range> batches_;
  std::vector<Range> adjacency_ranges_;
  GLsizei adjacency_count_ = 0;
  std::int64_t adjacency_bytes_ = 0;
};

// A vertex shader for draw_all and draw_casters: the scene's vertices
// projected by `uniform mat4 view_projection`, their world position, normal
// and texture coordinate passed on as v_world, v_normal and v_uv. It is the
// G-buffer's own vertex stage, here so that a technique passing on the same
// attributes (from the light or the camera) need not copy it.
extern const char* const kSceneVertexShader;

}  // namespace sb::gl
