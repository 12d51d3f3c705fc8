#pragma once
// The smooth surface that a triangle's corner normals define: a curved PN
// triangle (Vlachos et al. 2001), a cubic Bézier patch through the three
// corners, tangent there to the planes the normals give. Along an edge it is
// the cubic Hermite curve whose end tangents are the edge projected into
// those planes, so it depends on that edge's two corners and normals only:
// two triangles that share an edge and its normals share its curve, and the
// smooth silhouette stays watertight across them.
#include <array>
#include <glm/glm.hpp>

namespace sb::techniques::shadow_volume {

class PnTriangle {
 public:
  // Corners counter-clockwise; normals of unit length.
  PnTriangle(const std::array<glm::vec3, 3>& p, const std::array<glm::vec3, 3>& n);
  // The point at barycentric coordinates b (b.x + b.y + b.z = 1, b.x the
  // weight of corner 0).
  glm::vec3 point(const glm::vec3& b) const;
  // The linearly interpolated, normalised corner normal at b.
  glm::vec3 normal(const glm::vec3& b) const;

 private:
  std::array<glm::vec3, 3> n_;
  // b300 b030 b003 b210 b120 b021 b012 b102 b201 b111
  std::array<glm::vec3, 10> c_;
};

}  // namespace sb::techniques::shadow_volume
