#include "scenes/mesh_builders.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace sb {

using core::AnalyticShape;
using core::Mesh;

namespace {

constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

uint32_t next_index(const Mesh& m) { return uint32_t(m.positions.size()); }

void push_vertex(Mesh& m, glm::vec3 p, glm::vec3 n) {
  m.positions.push_back(p);
  m.normals.push_back(n);
}

// A right-handed frame (u, v, axis): rings traced by cos*u + sin*v run
// counter-clockwise seen from +axis.
void frame_around(glm::vec3 axis, glm::vec3& u, glm::vec3& v) {
  const glm::vec3 helper =
      std::fabs(axis.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  u = glm::normalize(glm::cross(helper, axis));
  v = glm::cross(axis, u);
}

glm::vec3 unit_axis(glm::vec3 axis, const char* who) {
  const float len = glm::length(axis);
  if (!(len > 0.0f) || !std::isfinite(len))
    throw std::invalid_argument(std::string(who) + ": zero or non-finite axis");
  return axis / len;
}

}  // namespace

Mesh make_box(const std::string& name, glm::vec3 center, glm::vec3 half_extents,
              const glm::mat3& rotation) {
  if (!(half_extents.x > 0.0f && half_extents.y > 0.0f && half_extents.z > 0.0f))
    throw std::invalid_argument("make_box: half extents must be positive");
  Mesh m;
  m.name = name;
  // Corners are computed once so the three faces meeting there share them exactly.
  glm::vec3 corners[8];
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 sign((i & 1) ? 1.0f : -1.0f, (i & 2) ? 1.0f : -1.0f, (i & 4) ? 1.0f : -1.0f);
    corners[i] = center + rotation * (sign * half_extents);
  }
  for (int axis = 0; axis < 3; ++axis)
    for (int side = -1; side <= 1; side += 2) {
      // e[axis+1] x e[axis+2] = e[axis]; swapping the tangents flips the face.
      int t1 = (axis + 1) % 3, t2 = (axis + 2) % 3;
      if (side < 0) std::swap(t1, t2);
      glm::vec3 n(0.0f);
      n[axis] = float(side);
      const glm::vec3 normal = glm::normalize(rotation * n);
      const uint32_t base = next_index(m);
      constexpr int kQuad[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (const auto& q : kQuad) {
        int bits[3] = {0, 0, 0};
        bits[axis] = side > 0;
        bits[t1] = q[0] > 0;
        bits[t2] = q[1] > 0;
        push_vertex(m, corners[bits[0] | (bits[1] << 1) | (bits[2] << 2)], normal);
      }
      m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
  return m;
}

Mesh make_cylinder(const std::string& name, glm::vec3 base_center, glm::vec3 axis,
                   float radius_bottom, float radius_top, float height, int segments) {
  if (segments < 3) throw std::invalid_argument("make_cylinder: needs at least 3 segments");
  if (!(height > 0.0f)) throw std::invalid_argument("make_cylinder: height must be positive");
  if (!(radius_bottom >= 0.0f && radius_top >= 0.0f) ||
      !(radius_bottom > 0.0f || radius_top > 0.0f))
    throw std::invalid_argument("make_cylinder: radii must be >= 0 and not both 0");
  const glm::vec3 w = unit_axis(axis, "make_cylinder");
  glm::vec3 u, v;
  frame_around(w, u, v);
  const glm::vec3 top_center = base_center + height * w;

  // Ring positions computed once, shared by the side and the caps.
  const size_t n = size_t(segments);
  std::vector<glm::vec3> dirs(n), bottom(n), top(n);
  for (int j = 0; j < segments; ++j) {
    const float phi = kTwoPi * float(j) / float(segments);
    dirs[size_t(j)] = std::cos(phi) * u + std::sin(phi) * v;
    bottom[size_t(j)] = base_center + radius_bottom * dirs[size_t(j)];
    top[size_t(j)] = top_center + radius_top * dirs[size_t(j)];
  }
  Mesh m;
  m.name = name;
  const bool bottom_apex = radius_bottom == 0.0f, top_apex = radius_top == 0.0f;
  const auto seg = [&](int j) { return size_t(j % segments); };

  // Side: the cone's normal tilts towards the narrow end by the slope.
  for (int j = 0; j < segments; ++j) {
    const glm::vec3 n0 = glm::normalize(height * dirs[seg(j)] + (radius_bottom - radius_top) * w);
    const glm::vec3 n1 =
        glm::normalize(height * dirs[seg(j + 1)] + (radius_bottom - radius_top) * w);
    const uint32_t base = next_index(m);
    push_vertex(m, bottom_apex ? base_center : bottom[seg(j)], n0);
    push_vertex(m, bottom_apex ? base_center : bottom[seg(j + 1)], n1);
    push_vertex(m, top_apex ? top_center : top[seg(j + 1)], n1);
    push_vertex(m, top_apex ? top_center : top[seg(j)], n0);
    // (b_j, b_j+1, t_j+1) is counter-clockwise seen from outside: tangent x axis = radial.
    if (!bottom_apex && !top_apex)
      m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    else if (bottom_apex)
      m.indices.insert(m.indices.end(), {base, base + 2, base + 3});
    else
      m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
  }
  // Caps: fans with flat normals, counter-clockwise seen from -axis / +axis.
  if (!bottom_apex) {
    const uint32_t c = next_index(m);
    push_vertex(m, base_center, -w);
    for (int j = 0; j < segments; ++j) push_vertex(m, bottom[seg(j)], -w);
    for (uint32_t j = 0; j < uint32_t(segments); ++j)
      m.indices.insert(m.indices.end(), {c, c + 1 + (j + 1) % uint32_t(segments), c + 1 + j});
  }
  if (!top_apex) {
    const uint32_t c = next_index(m);
    push_vertex(m, top_center, w);
    for (int j = 0; j < segments; ++j) push_vertex(m, top[seg(j)], w);
    for (uint32_t j = 0; j < uint32_t(segments); ++j)
      m.indices.insert(m.indices.end(), {c, c + 1 + j, c + 1 + (j + 1) % uint32_t(segments)});
  }
  return m;
}

Mesh make_torus(const std::string& name, glm::vec3 center, glm::vec3 axis, float major, float minor,
                int segments_major, int segments_minor) {
  if (segments_major < 3 || segments_minor < 3)
    throw std::invalid_argument("make_torus: needs at least 3 segments each way");
  if (!(minor > 0.0f && major > minor))
    throw std::invalid_argument("make_torus: needs 0 < minor < major");
  const glm::vec3 w = unit_axis(axis, "make_torus");
  glm::vec3 u, v;
  frame_around(w, u, v);
  Mesh m;
  m.name = name;
  // One vertex per grid point with indices wrapping both ways: closed without welding.
  for (int i = 0; i < segments_major; ++i) {
    const float theta = kTwoPi * float(i) / float(segments_major);
    const glm::vec3 d = std::cos(theta) * u + std::sin(theta) * v;
    for (int j = 0; j < segments_minor; ++j) {
      const float phi = kTwoPi * float(j) / float(segments_minor);
      const glm::vec3 n = std::cos(phi) * d + std::sin(phi) * w;
      push_vertex(m, center + major * d + minor * n, n);
    }
  }
  const auto at = [&](int i, int j) {
    return uint32_t((i % segments_major) * segments_minor + (j % segments_minor));
  };
  // d(theta) x d(phi) points outward from the tube's centre line.
  for (int i = 0; i < segments_major; ++i)
    for (int j = 0; j < segments_minor; ++j) {
      const uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
    }
  return m;
}

void transform_mesh(Mesh& mesh, const glm::mat4& transform) {
  const glm::mat3 linear(transform);
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(linear));
  for (auto& p : mesh.positions) p = glm::vec3(transform * glm::vec4(p, 1.0f));
  for (auto& n : mesh.normals) {
    const glm::vec3 t = normal_matrix * n;
    const float len = glm::length(t);
    if (len > 0.0f) n = t / len;
  }
  if (glm::determinant(linear) < 0.0f)
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
      std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
  if (mesh.analytic.kind == AnalyticShape::Kind::Sphere) {
    // A sphere stays one under a similarity (rotation, mirror, uniform scale).
    const float scale = std::cbrt(std::fabs(glm::determinant(linear)));
    const glm::mat3 gram = glm::transpose(linear) * linear;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (std::fabs(gram[i][j] - (i == j ? scale * scale : 0.0f)) > 1e-5f * scale * scale)
          throw std::invalid_argument("transform_mesh: mesh '" + mesh.name +
                                      "' has an analytic sphere, which a transform that is no "
                                      "similarity does not keep a sphere");
    mesh.analytic.center = glm::vec3(transform * glm::vec4(mesh.analytic.center, 1.0f));
    mesh.analytic.radius *= scale;
  }
}

void append_mesh(Mesh& dst, const Mesh& src) {
  if (dst.analytic.has() || src.analytic.has())
    throw std::invalid_argument("append_mesh: '" + src.name + "' into '" + dst.name +
                                "': a mesh with an analytic shape cannot be merged (the shape "
                                "would not describe the result)");
  const uint32_t offset = next_index(dst);
  const size_t old_count = dst.positions.size();
  dst.positions.insert(dst.positions.end(), src.positions.begin(), src.positions.end());
  dst.normals.insert(dst.normals.end(), src.normals.begin(), src.normals.end());
  // Texture coordinates stay per vertex: missing ones become (0, 0).
  if (!dst.uvs.empty() || !src.uvs.empty()) {
    dst.uvs.resize(old_count, glm::vec2(0.0f));
    if (src.uvs.size() == src.positions.size())
      dst.uvs.insert(dst.uvs.end(), src.uvs.begin(), src.uvs.end());
    else
      dst.uvs.resize(dst.positions.size(), glm::vec2(0.0f));
  }
  // No reserve(size + n) here: called once per part, an exact reserve would
  // reallocate every time (quadratic); push_back grows geometrically.
  for (const uint32_t i : src.indices) dst.indices.push_back(i + offset);
}

}  // namespace sb
