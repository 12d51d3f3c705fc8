#include "scenes/gltf_primitives.h"

#include <cstring>

#include "scenes/gltf_import.h"

namespace sb::gltf {

LoadedPrimitive PrimitiveLoader::load_primitive(size_t mesh_index, size_t prim_index) {
  const tg::Mesh& mesh = model_.meshes[mesh_index];
  const tg::Primitive& p = mesh.primitives[prim_index];
  const std::string where = named("mesh", mesh.name, mesh_index) + " primitive " + str(prim_index);
  const int mode = p.mode;
  if (mode < 0 || mode > 6)
    fail(where, "mode " + std::to_string(mode) + " is not a primitive mode");
  static const char* lower_modes[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
  if (mode >= 0 && mode <= 3)
    fail(where, "mode " + std::string(lower_modes[mode]) + " (" + std::to_string(mode) +
                    ") is not supported: only triangles, triangle strips and fans are");

  const auto attribute = [&](const std::string& name) {
    const auto it = p.attributes.find(name);
    return it == p.attributes.end() ? -1 : it->second;
  };
  const int position = attribute("POSITION");
  if (position < 0) fail(where, "has no POSITION attribute");

  // Count the triangles before reading anything big.
  const tg::Accessor& pa = accessors_.accessor(position, "POSITION of " + where);
  accessors_.check_count(pa, accessor_where(position, "POSITION of " + where));
  size_t elements = pa.count;
  if (p.indices >= 0) {
    const tg::Accessor& ia = accessors_.accessor(p.indices, "indices of " + where);
    accessors_.check_count(ia, accessor_where(p.indices, "indices of " + where));
    elements = ia.count;
  }
  if (mode == TINYGLTF_MODE_TRIANGLES && elements % 3 != 0)
    fail(where, "TRIANGLES with " + str(elements) + " vertices or indices, not a multiple of 3");
  const size_t triangles = mode == TINYGLTF_MODE_TRIANGLES ? elements / 3
                           : elements >= 3                 ? elements - 2
                                                           : 0;
  if (triangles > kGltfMaxTriangles)
    fail(where, str(triangles) + " triangles exceed the limit of " + str(kGltfMaxTriangles));

  LoadedPrimitive out;
  const MaterialInfo mat = materials_.material(p.material, where);
  out.albedo = mat.albedo;
  out.texture = mat.texture;
  out.alpha_mode = mat.mode;
  out.alpha_cutoff = mat.cutoff;
  out.double_sided = mat.double_sided;

  const std::vector<float> pos = accessors_.read_floats(position, 3, "POSITION of " + where);
  const size_t n = pos.size() / 3;
  out.positions.resize(n);
  std::memcpy(out.positions.data(), pos.data(), pos.size() * sizeof(float));

  if (const int normal = attribute("NORMAL"); normal >= 0) {
    const std::vector<float> nor = accessors_.read_floats(normal, 3, "NORMAL of " + where);
    if (nor.size() != pos.size())
      fail(where, "NORMAL has " + str(nor.size() / 3) + " elements but POSITION has " + str(n));
    out.normals.resize(n);
    std::memcpy(out.normals.data(), nor.data(), nor.size() * sizeof(float));
  }

  const std::string uv_name = "TEXCOORD_" + std::to_string(mat.texcoord);
  const int uv = attribute(uv_name);
  if (mat.texture >= 0 && uv < 0)
    fail(where, "its material's baseColorTexture uses " + uv_name + ", which it does not have");
  if (uv >= 0) {
    const std::vector<float> tc = accessors_.read_floats(uv, 2, uv_name + " of " + where);
    if (tc.size() / 2 != n)
      fail(where, uv_name + " has " + str(tc.size() / 2) + " elements but POSITION has " + str(n));
    out.uvs.resize(n);
    for (size_t i = 0; i < n; ++i) {
      glm::dvec3 t(tc[2 * i], tc[2 * i + 1], 1.0);
      if (mat.transform) t = mat.uv_transform * t;
      out.uvs[i] = glm::vec2(float(t.x), float(t.y));
    }
  }

  std::vector<uint32_t> idx;
  if (p.indices >= 0) {
    idx = accessors_.read_indices(p.indices, "indices of " + where, n);
  } else {
    idx.resize(n);
    for (size_t i = 0; i < n; ++i) idx[i] = uint32_t(i);
  }
  out.indices.reserve(triangles * 3);
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    out.indices = std::move(idx);
  } else {
    for (size_t i = 0; i < triangles; ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLE_FAN)
        out.indices.insert(out.indices.end(), {idx[0], idx[i + 1], idx[i + 2]});
      else if (i % 2 == 0)  // strips alternate winding
        out.indices.insert(out.indices.end(), {idx[i], idx[i + 1], idx[i + 2]});
      else
        out.indices.insert(out.indices.end(), {idx[i + 1], idx[i], idx[i + 2]});
    }
  }
  return out;
}

const std::vector<LoadedPrimitive>& PrimitiveLoader::mesh_primitives(size_t mesh_index) {
  auto it = loaded_.find(mesh_index);
  if (it != loaded_.end()) return it->second;
  std::vector<LoadedPrimitive> prims;
  const tg::Mesh& mesh = model_.meshes[mesh_index];
  for (size_t i = 0; i < mesh.primitives.size(); ++i)
    prims.push_back(load_primitive(mesh_index, i));
  return loaded_.emplace(mesh_index, std::move(prims)).first->second;
}

}  // namespace sb::gltf
