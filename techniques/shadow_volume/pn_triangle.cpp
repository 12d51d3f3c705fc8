#include "shadow_volume/pn_triangle.h"

namespace sb::techniques::shadow_volume {

namespace {
// The control point one third along the edge from corner a towards b,
// projected into a's tangent plane.
glm::vec3 edge_control(const glm::vec3& a, const glm::vec3& b, const glm::vec3& na) {
  return (2.0f * a + b - glm::dot(b - a, na) * na) / 3.0f;
}
}  // namespace

PnTriangle::PnTriangle(const std::array<glm::vec3, 3>& p, const std::array<glm::vec3, 3>& n)
    : n_(n) {
  c_[0] = p[0];
  c_[1] = p[1];
  c_[2] = p[2];
  c_[3] = edge_control(p[0], p[1], n[0]);  // b210
  c_[4] = edge_control(p[1], p[0], n[1]);  // b120
  c_[5] = edge_control(p[1], p[2], n[1]);  // b021
  c_[6] = edge_control(p[2], p[1], n[2]);  // b012
  c_[7] = edge_control(p[2], p[0], n[2]);  // b102
  c_[8] = edge_control(p[0], p[2], n[0]);  // b201
  const glm::vec3 e = (c_[3] + c_[4] + c_[5] + c_[6] + c_[7] + c_[8]) / 6.0f;
  const glm::vec3 v = (p[0] + p[1] + p[2]) / 3.0f;
  c_[9] = e + 0.5f * (e - v);  // b111
}

glm::vec3 PnTriangle::point(const glm::vec3& b) const {
  const float u = b.x, v = b.y, w = b.z;
  return c_[0] * (u * u * u) + c_[1] * (v * v * v) + c_[2] * (w * w * w) +
         3.0f * (c_[3] * (u * u * v) + c_[4] * (u * v * v) + c_[5] * (v * v * w) +
                 c_[6] * (v * w * w) + c_[7] * (u * w * w) + c_[8] * (u * u * w)) +
         6.0f * c_[9] * (u * v * w);
}

glm::vec3 PnTriangle::normal(const glm::vec3& b) const {
  const glm::vec3 n = b.x * n_[0] + b.y * n_[1] + b.z * n_[2];
  const float len = glm::length(n);
  return len > 0.0f ? n / len : n_[0];
}

}  // namespace sb::techniques::shadow_volume
