#include "raytraced/gpu_casters.h"

#include <cstring>
#include <map>
#include <string>

#include "core/error.h"
#include "gl/debug.h"

namespace sb::techniques::raytraced {

namespace {

float as_float(uint32_t u) {
  float f = 0.0f;
  std::memcpy(&f, &u, 4);
  return f;
}

// A buffer of `data`, at least one vec4 (GL makes no storage of 0 bytes).
template <typename T>
gl::Buffer upload(std::vector<T> data) {
  if (data.size() * sizeof(T) < 16) data.resize((16 + sizeof(T) - 1) / sizeof(T));
  return gl::make_buffer(GLsizeiptr(data.size() * sizeof(T)), data.data());
}

}  // namespace

CasterSet collect_casters(const core::Scene& scene) {
  CasterSet out;
  for (const core::Mesh& m : scene.meshes) {
    if (!m.casts_shadow) continue;
    const bool masked = m.alpha_tested();
    if (masked && (m.uvs.size() != m.positions.size() ||
                   size_t(m.base_color_texture) >= scene.textures.size()))
      throw core::InputError("", "mesh '" + m.name + "'",
                             "alpha-tested without per-vertex uvs or with a missing texture");
    for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
      const uint32_t a = m.indices[i], b = m.indices[i + 1], c = m.indices[i + 2];
      if (a >= m.positions.size() || b >= m.positions.size() || c >= m.positions.size())
        throw core::InputError("", "mesh '" + m.name + "'", "index beyond the vertex count");
      out.triangles.push_back({m.positions[a], m.positions[b], m.positions[c]});
      if (!masked) {
        out.mask_of.push_back(-1);
        continue;
      }
      out.mask_of.push_back(int(out.masks.size()));
      out.masks.push_back({{m.uvs[a], m.uvs[b], m.uvs[c]}, m.base_color_texture, m.alpha_cutoff});
    }
  }
  return out;
}

GpuCasters::GpuCasters(const core::Scene& scene, int leaf_size) {
  const CasterSet set = collect_casters(scene);
  const ShadowBvh bvh = build_shadow_bvh(set.triangles, leaf_size);
  node_count_ = bvh.nodes.size();
  depth_ = bvh.depth;

  std::vector<glm::vec4> nodes;
  nodes.reserve(2 * bvh.nodes.size());
  for (const BvhNode& n : bvh.nodes) {  // a leaf's skip is the next node: not stored
    nodes.emplace_back(n.lo, as_float(n.leaf() ? n.first : n.skip));
    nodes.emplace_back(n.hi, as_float(n.count));
  }
  std::vector<glm::vec4> tris;
  tris.reserve(3 * bvh.order.size());
  for (uint32_t t : bvh.order) {
    const BvhTriangle& tri = set.triangles[t];
    const int mask = set.mask_of[t];
    tris.emplace_back(tri.a, as_float(mask < 0 ? 0xffffffffu : uint32_t(mask)));
    tris.emplace_back(tri.b, 0.0f);
    tris.emplace_back(tri.c, 0.0f);
  }
  // The mask textures, each once, in first-use order.
  std::map<int, uint32_t> slot_of;
  std::vector<uint32_t> textures;
  std::vector<uint8_t> alpha_bytes;
  std::vector<glm::vec4> masks;
  masks.reserve(2 * set.masks.size());
  for (const CasterSet::Mask& m : set.masks) {
    auto [it, added] = slot_of.emplace(m.texture, uint32_t(textures.size() / 4));
    if (added) {
      const core::TextureImage& img = scene.textures[size_t(m.texture)];
      textures.insert(textures.end(), {uint32_t(alpha_bytes.size()), uint32_t(img.width),
                                       uint32_t(img.height), 0u});
      for (size_t p = 0; p < size_t(img.width) * size_t(img.height); ++p)
        alpha_bytes.push_back(img.rgba[p * 4 + 3]);
    }
    masks.emplace_back(m.uv[0], m.uv[1]);
    masks.emplace_back(m.uv[2], as_float(it->second), m.cutoff);
  }
  std::vector<uint32_t> alphas((alpha_bytes.size() + 3) / 4, 0u);
  for (size_t i = 0; i < alpha_bytes.size(); ++i)
    alphas[i / 4] |= uint32_t(alpha_bytes[i]) << (8 * (i % 4));

  nodes_ = upload(std::move(nodes));
  triangles_ = upload(std::move(tris));
  masks_ = upload(std::move(masks));
  textures_ = upload(std::move(textures));
  alphas_ = upload(std::move(alphas));
  gl::throw_if_errors("raytraced: uploading the casters");
}

void GpuCasters::bind() const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, nodes_.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, triangles_.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, masks_.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, textures_.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, alphas_.get());
}

}  // namespace sb::techniques::raytraced
