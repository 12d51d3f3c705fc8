#include "scenes/gltf_traversal.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <numbers>

#include "scenes/gltf_import.h"

namespace sb::gltf {

using core::Mesh;

namespace {

bool casts_shadow_flag(const tg::Value& extras, bool def) {
  const tg::Value* sb = member(extras, "shadowbench_mesh");
  const tg::Value* flag = sb ? member(*sb, "casts_shadow") : nullptr;
  return flag != nullptr && flag->IsBool() ? flag->Get<bool>() : def;
}

}  // namespace

void Traversal::run() {
  const std::vector<int> parent = check_hierarchy();
  std::vector<size_t> roots;
  if (!model_.scenes.empty()) {
    int si = model_.defaultScene < 0 ? 0 : model_.defaultScene;
    if (size_t(si) >= model_.scenes.size())
      fail("scene", "the default scene " + std::to_string(si) + " does not exist (" +
                        str(model_.scenes.size()) + " scenes)");
    const tg::Scene& s = model_.scenes[size_t(si)];
    for (int r : s.nodes) {
      if (r < 0 || size_t(r) >= model_.nodes.size())
        fail(named("scene", s.name, size_t(si)), "node " + std::to_string(r) + " does not exist (" +
                                                     str(model_.nodes.size()) + " nodes)");
      if (parent[size_t(r)] >= 0)
        fail(named("node", model_.nodes[size_t(r)].name, size_t(r)),
             "is a root of the scene but also the child of node " +
                 std::to_string(parent[size_t(r)]));
      roots.push_back(size_t(r));
    }
    if (const tg::Value* sb = member(s.extras, "shadowbench_scene")) {
      const tg::Value* a = member(*sb, "ambient");
      double c[3];
      if (a != nullptr && a->IsArray() && a->ArrayLen() == 3 && finite_number(&a->Get(0), c[0]) &&
          finite_number(&a->Get(1), c[1]) && finite_number(&a->Get(2), c[2]))
        scene_.ambient = glm::vec3(float(c[0]), float(c[1]), float(c[2]));
    }
  } else {  // no scenes: every root node
    for (size_t i = 0; i < model_.nodes.size(); ++i)
      if (parent[i] < 0) roots.push_back(i);
  }
  // Depth-first, in file order, without recursion (hierarchies can be deep).
  std::vector<std::pair<size_t, glm::dmat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, glm::dmat4(1.0));
  while (!stack.empty()) {
    const auto [index, parent_world] = stack.back();
    stack.pop_back();
    const tg::Node& node = model_.nodes[index];
    const std::string where = named("node", node.name, index);
    const glm::dmat4 world = parent_world * local_matrix(node, where);
    if (node.mesh != -1) instantiate(index, world);
    if (node.camera != -1 && !camera_.found) visit_camera(index, world);
    if (!light_.found) visit_light(index, world);
    for (auto c = node.children.rbegin(); c != node.children.rend(); ++c)
      stack.emplace_back(size_t(*c), world);
  }
}

glm::dmat4 Traversal::local_matrix(const tg::Node& n, const std::string& where) const {
  const auto finite = [&](const std::vector<double>& v, const char* what) {
    for (double x : v)
      if (!std::isfinite(x)) fail(where, std::string(what) + " is not finite");
  };
  if (!n.matrix.empty()) {
    if (n.matrix.size() != 16)
      fail(where, "matrix has " + str(n.matrix.size()) + " numbers, expected 16");
    if (!n.translation.empty() || !n.rotation.empty() || !n.scale.empty())
      fail(where, "has both a matrix and translation/rotation/scale");
    finite(n.matrix, "matrix");
    glm::dmat4 m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m[c][r] = n.matrix[size_t(c) * 4 + size_t(r)];
    return m;
  }
  glm::dmat4 t(1.0), r(1.0), s(1.0);
  if (!n.translation.empty()) {
    if (n.translation.size() != 3) fail(where, "translation: expected 3 numbers");
    finite(n.translation, "translation");
    t[3] = glm::dvec4(n.translation[0], n.translation[1], n.translation[2], 1.0);
  }
  if (!n.rotation.empty()) {
    if (n.rotation.size() != 4) fail(where, "rotation: expected 4 numbers (x, y, z, w)");
    finite(n.rotation, "rotation");
    glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    const double len = glm::length(q);
    if (!(len > 1e-6)) fail(where, "rotation is not a unit quaternion");
    r = glm::mat4_cast(q / len);
  }
  if (!n.scale.empty()) {
    if (n.scale.size() != 3) fail(where, "scale: expected 3 numbers");
    finite(n.scale, "scale");
    s = glm::scale(glm::dmat4(1.0), glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  }
  return t * r * s;
}

// Children must form a forest: one parent each, no cycles.
std::vector<int> Traversal::check_hierarchy() const {
  const size_t n = model_.nodes.size();
  std::vector<int> parent(n, -1);
  for (size_t i = 0; i < n; ++i) {
    const tg::Node& node = model_.nodes[i];
    for (int c : node.children) {
      const std::string where = named("node", node.name, i);
      if (c < 0 || size_t(c) >= n)
        fail(where, "child " + std::to_string(c) + " does not exist (" + str(n) + " nodes)");
      if (size_t(c) == i) fail(where, "is its own child");
      if (parent[size_t(c)] >= 0)
        fail(named("node", model_.nodes[size_t(c)].name, size_t(c)),
             "has two parents, nodes " + std::to_string(parent[size_t(c)]) + " and " + str(i) +
                 " (the node hierarchy must be a tree)");
      parent[size_t(c)] = int(i);
    }
  }
  std::vector<char> state(n, 0);  // 0 unseen, 1 on the current walk, 2 known to end at a root
  for (size_t i = 0; i < n; ++i) {
    std::vector<size_t> walk;
    int x = int(i);
    while (x >= 0 && state[size_t(x)] == 0) {
      state[size_t(x)] = 1;
      walk.push_back(size_t(x));
      x = parent[size_t(x)];
    }
    if (x >= 0 && state[size_t(x)] == 1)
      fail(named("node", model_.nodes[size_t(x)].name, size_t(x)),
           "is its own ancestor: the node hierarchy has a cycle");
    for (size_t w : walk) state[w] = 2;
  }
  return parent;
}

void Traversal::instantiate(size_t node_index, const glm::dmat4& world) {
  const tg::Node& node = model_.nodes[node_index];
  const std::string where = named("node", node.name, node_index);
  if (size_t(node.mesh) >= model_.meshes.size())
    fail(where, "mesh " + std::to_string(node.mesh) + " does not exist (" +
                    str(model_.meshes.size()) + " meshes)");
  const glm::dmat3 linear(world);
  const double det = glm::determinant(linear);
  if (det == 0.0) return;  // zero scale: nothing visible (documented)
  const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear));
  const bool mirrored = det < 0.0;

  const tg::Mesh& gmesh = model_.meshes[size_t(node.mesh)];
  const std::vector<LoadedPrimitive>& prims = primitives_.mesh_primitives(size_t(node.mesh));
  const bool casts = casts_shadow_flag(node.extras, casts_shadow_flag(gmesh.extras, true));
  for (size_t pi = 0; pi < prims.size(); ++pi) {
    const LoadedPrimitive& p = prims[pi];
    const size_t triangles = p.indices.size() / 3;
    if (triangles == 0) continue;
    if (triangles > kGltfMaxTriangles - total_triangles_)
      fail(where, "the scene exceeds the limit of " + str(kGltfMaxTriangles) +
                      " triangles (after instancing)");
    total_triangles_ += triangles;

    Mesh m;
    m.name = !node.name.empty()    ? node.name
             : !gmesh.name.empty() ? gmesh.name
                                   : "mesh" + std::to_string(node.mesh);
    if (prims.size() > 1) m.name += "/" + str(pi);
    m.albedo = p.albedo;
    m.base_color_texture = p.texture;
    m.alpha_mode = p.alpha_mode;
    m.alpha_cutoff = p.alpha_cutoff;
    m.double_sided = p.double_sided;
    m.casts_shadow = casts;

    std::vector<glm::vec3> positions(p.positions.size());
    for (size_t i = 0; i < positions.size(); ++i) {
      const glm::dvec3 q = glm::dvec3(world * glm::dvec4(glm::dvec3(p.positions[i]), 1.0));
      positions[i] = glm::vec3(q);
      if (!std::isfinite(positions[i].x) || !std::isfinite(positions[i].y) ||
          !std::isfinite(positions[i].z))
        fail(where,
             "its transform takes a vertex of mesh " + std::to_string(node.mesh) + " to infinity");
    }
    std::vector<uint32_t> indices = p.indices;
    if (mirrored)  // a mirroring transform turns counter-clockwise into clockwise
      for (size_t t = 0; t < indices.size(); t += 3) std::swap(indices[t + 1], indices[t + 2]);

    if (!p.normals.empty()) {
      m.positions = std::move(positions);
      m.indices = std::move(indices);
      m.uvs = p.uvs;
      m.normals.resize(p.normals.size());
      for (size_t i = 0; i < p.normals.size(); ++i) {
        const glm::dvec3 nv = normal_matrix * glm::dvec3(p.normals[i]);
        const double len = glm::length(nv);
        m.normals[i] = len > 0 ? glm::vec3(nv / len) : glm::vec3(0.0f);
      }
    } else {
      // glTF: without normals, flat shading (one vertex per corner).
      m.positions.reserve(indices.size());
      m.normals.reserve(indices.size());
      if (!p.uvs.empty()) m.uvs.reserve(indices.size());
      for (size_t t = 0; t < indices.size(); t += 3) {
        const glm::vec3 a = positions[indices[t]], b = positions[indices[t + 1]],
                        c = positions[indices[t + 2]];
        const glm::vec3 cr = glm::cross(b - a, c - a);
        const float len = glm::length(cr);
        const glm::vec3 n = len > 0 ? cr / len : glm::vec3(0.0f, 1.0f, 0.0f);
        for (int k = 0; k < 3; ++k) {
          m.positions.push_back(positions[indices[t + size_t(k)]]);
          m.normals.push_back(n);
          if (!p.uvs.empty()) m.uvs.push_back(p.uvs[indices[t + size_t(k)]]);
          m.indices.push_back(uint32_t(t + size_t(k)));
        }
      }
    }
    scene_.meshes.push_back(std::move(m));
  }
}

void Traversal::visit_camera(size_t node_index, const glm::dmat4& world) {
  const tg::Node& node = model_.nodes[node_index];
  const std::string nwhere = named("node", node.name, node_index);
  if (size_t(node.camera) >= model_.cameras.size())
    fail(nwhere, "camera " + std::to_string(node.camera) + " does not exist (" +
                     str(model_.cameras.size()) + " cameras)");
  const tg::Camera& cam = model_.cameras[size_t(node.camera)];
  if (cam.type != "perspective") return;  // orthographic cameras are skipped (documented)
  const std::string where = named("camera", cam.name, size_t(node.camera));
  const auto& p = cam.perspective;
  if (!std::isfinite(p.yfov) || p.yfov <= 0 || p.yfov >= std::numbers::pi)
    fail(where, "yfov " + json(p.yfov).dump() + " is outside (0, pi) radians");
  if (!std::isfinite(p.znear) || p.znear <= 0)
    fail(where, "znear " + json(p.znear).dump() + " must be positive");
  if (!std::isfinite(p.zfar) || (p.zfar != 0 && p.zfar <= p.znear))
    fail(where, "zfar " + json(p.zfar).dump() + " must be greater than znear");
  camera_.eye = glm::dvec3(world[3]);
  camera_.forward = glm::dvec3(world * glm::dvec4(0, 0, -1, 0));
  camera_.up = glm::dvec3(world * glm::dvec4(0, 1, 0, 0));
  if (!(glm::length(camera_.forward) > 0) || !(glm::length(camera_.up) > 0) ||
      glm::length(glm::cross(camera_.forward, camera_.up)) == 0)
    fail(nwhere, "the camera's transform is degenerate");
  camera_.forward = glm::normalize(camera_.forward);
  camera_.up = glm::normalize(camera_.up);
  camera_.yfov = p.yfov;
  camera_.znear = p.znear;
  camera_.zfar = p.zfar;
  const tg::Value* sb = member(node.extras, "shadowbench_camera");
  double d = 0;
  if (sb != nullptr && finite_number(member(*sb, "target_distance"), d) && d > 0)
    camera_.distance = d;
  camera_.found = true;
}

bool Traversal::visit_light(size_t node_index, const glm::dmat4& world) {
  const tg::Node& node = model_.nodes[node_index];
  const auto ext = node.extensions.find("KHR_lights_punctual");
  if (ext == node.extensions.end()) return false;
  const std::string nwhere = named("node", node.name, node_index);
  const tg::Value* li = member(ext->second, "light");
  if (li == nullptr || !li->IsInt())
    fail(nwhere, "KHR_lights_punctual: expected {\"light\": index}");
  const int index = li->Get<int>();
  if (index < 0 || size_t(index) >= model_.lights.size())
    fail(nwhere, "KHR_lights_punctual light " + std::to_string(index) + " does not exist (" +
                     str(model_.lights.size()) + " lights)");
  const tg::Light& l = model_.lights[size_t(index)];
  if (l.type != "spot" && l.type != "point" && l.type != "directional")
    fail(named("light", l.name, size_t(index)),
         "type " + quoted(l.type) + " is not spot, point or directional");
  light_.type = l.type;
  light_.position = glm::dvec3(world[3]);
  light_.direction = glm::dvec3(world * glm::dvec4(0, 0, -1, 0));
  light_.x_axis = glm::dvec3(world * glm::dvec4(1, 0, 0, 0));
  if (!(glm::length(light_.direction) > 0) || !(glm::length(light_.x_axis) > 0))
    fail(nwhere, "the light's transform is degenerate");
  light_.direction = glm::normalize(light_.direction);
  if (const tg::Value* sb = member(node.extras, "shadowbench_light")) {
    const std::string w = nwhere + " extras.shadowbench_light";
    if (const tg::Value* size = member(*sb, "size")) {
      if (!size->IsArray() || size->ArrayLen() != 2 ||
          !finite_number(&size->Get(0), light_.width) ||
          !finite_number(&size->Get(1), light_.height) || light_.width < 0 || light_.height < 0)
        fail(w, "size: expected [width, height], two non-negative numbers");
    }
    if (member(*sb, "intensity") != nullptr &&
        (!finite_number(member(*sb, "intensity"), light_.intensity) || light_.intensity < 0))
      fail(w, "intensity: expected a non-negative number");
    double d = 0;
    if (finite_number(member(*sb, "target_distance"), d) && d > 0) light_.distance = d;
    if (member(*sb, "angular_diameter") != nullptr &&
        (!finite_number(member(*sb, "angular_diameter"), light_.angular_diameter) ||
         !(light_.angular_diameter >= 1e-4 && light_.angular_diameter <= 90)))
      fail(w, "angular_diameter: expected the sun's diameter in degrees in [0.0001, 90]");
  }
  light_.found = true;
  return true;
}

}  // namespace sb::gltf
