#include "common/convex_body.h"

#include <algorithm>
#include <cmath>

namespace sb::techniques {

using core::Bounds;
using core::Mesh;
using core::Scene;

namespace {

float side(const glm::vec4& plane, const glm::vec3& p) {
  return glm::dot(glm::vec3(plane), p) + plane.w;
}

// Orders the points of a planar convex polygon by angle about their centroid.
void order_about_centroid(std::vector<glm::vec3>& points, const glm::vec3& normal) {
  glm::vec3 c(0.0f);
  for (const auto& p : points) c += p;
  c /= float(points.size());
  const glm::vec3 a = glm::normalize(
      glm::cross(normal, std::fabs(normal.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
  const glm::vec3 b = glm::cross(normal, a);
  std::sort(points.begin(), points.end(), [&](const glm::vec3& p, const glm::vec3& q) {
    return std::atan2(glm::dot(p - c, b), glm::dot(p - c, a)) <
           std::atan2(glm::dot(q - c, b), glm::dot(q - c, a));
  });
}

}  // namespace

ConvexBody ConvexBody::box(const Bounds& b) {
  ConvexBody body;
  if (b.empty()) return body;
  const auto corner = [&](int i) {
    return glm::vec3((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y,
                     (i & 4) ? b.hi.z : b.lo.z);
  };
  // Each face: the four corners with one coordinate bit fixed, in cyclic order.
  for (int axis = 0; axis < 3; ++axis) {
    const int u = 1 << ((axis + 1) % 3), v = 1 << ((axis + 2) % 3);
    for (const int fixed : {0, 1 << axis})
      body.faces_.push_back(
          {corner(fixed), corner(fixed | u), corner(fixed | u | v), corner(fixed | v)});
  }
  return body;
}

void ConvexBody::clip(const glm::vec4& plane) {
  std::vector<std::vector<glm::vec3>> kept;
  std::vector<glm::vec3> cap;  // the new face, on the plane
  for (const auto& face : faces_) {
    std::vector<glm::vec3> out;
    for (size_t i = 0; i < face.size(); ++i) {
      const glm::vec3& a = face[i];
      const glm::vec3& b = face[(i + 1) % face.size()];
      const float sa = side(plane, a), sb = side(plane, b);
      if (sa >= 0.0f) out.push_back(a);
      if ((sa >= 0.0f) != (sb >= 0.0f)) {
        const glm::vec3 p = a + (b - a) * (sa / (sa - sb));
        out.push_back(p);
        cap.push_back(p);
      }
    }
    // A face cut to a point or a segment bounds nothing.
    if (out.size() >= 3) kept.push_back(std::move(out));
  }
  if (cap.size() >= 3) {
    order_about_centroid(cap, glm::vec3(plane));
    kept.push_back(std::move(cap));
  }
  // A flat body (a ground plane's box) keeps its two coinciding faces.
  faces_ = std::move(kept);
}

std::vector<glm::vec3> ConvexBody::vertices() const {
  std::vector<glm::vec3> v;
  for (const auto& f : faces_) v.insert(v.end(), f.begin(), f.end());
  return v;
}

std::vector<glm::vec4> frustum_planes(const glm::mat4& m) {
  const glm::vec4 row0(m[0][0], m[1][0], m[2][0], m[3][0]);
  const glm::vec4 row1(m[0][1], m[1][1], m[2][1], m[3][1]);
  const glm::vec4 row2(m[0][2], m[1][2], m[2][2], m[3][2]);
  const glm::vec4 row3(m[0][3], m[1][3], m[2][3], m[3][3]);
  return {row3 + row0, row3 - row0, row3 + row1, row3 - row1, row3 + row2, row3 - row2};
}

std::vector<Bounds> mesh_boxes(const Scene& scene) {
  std::vector<Bounds> boxes;
  boxes.reserve(scene.meshes.size());
  for (const Mesh& m : scene.meshes) {
    Bounds b;
    for (const auto& p : m.positions) b.extend(p);
    boxes.push_back(b);
  }
  return boxes;
}

std::vector<glm::vec3> visible_body(const std::vector<Bounds>& boxes,
                                    const std::vector<glm::vec4>& planes) {
  std::vector<glm::vec3> points;
  for (const Bounds& b : boxes) {
    ConvexBody body = ConvexBody::box(b);
    // A flat box (a ground plane's) has side faces of zero area; its two
    // large faces still clip to the visible part of the plane.
    for (const auto& plane : planes) {
      if (body.empty()) break;
      body.clip(plane);
    }
    const auto v = body.vertices();
    points.insert(points.end(), v.begin(), v.end());
  }
  return points;
}

}  // namespace sb::techniques
