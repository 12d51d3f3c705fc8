#include "scenes/outdoor_parts.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "scenes/leaf.h"
#include "scenes/mesh_builders.h"

namespace sb {

using core::Mesh;

namespace {

constexpr glm::vec3 kUp(0.0f, 1.0f, 0.0f);

// The rotation by `yaw` about y: local x to (cos, 0, −sin), local z to (sin, 0, cos).
glm::mat3 yaw_rotation(float yaw) {
  const float c = std::cos(yaw), s = std::sin(yaw);
  return glm::mat3(glm::vec3(c, 0.0f, -s), kUp, glm::vec3(s, 0.0f, c));
}

glm::vec3 ground(glm::vec2 at) { return {at.x, 0.0f, at.y}; }

// Uniform on the unit sphere.
glm::vec3 random_direction(Draws& draws) {
  const float z = draws.uniform(-1.0f, 1.0f);
  const float phi = draws.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(phi), z, r * std::sin(phi)};
}

void add_leaf(Mesh& leaves, glm::vec3 stalk, glm::vec3 outwards, float size, Draws& draws) {
  // The blade points outwards, scattered; it turns about itself at random.
  glm::vec3 v = outwards + 0.7f * random_direction(draws);
  v = glm::length(v) > 1e-3f ? glm::normalize(v) : outwards;
  const glm::vec3 any = std::fabs(v.y) < 0.9f ? kUp : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 u0 = glm::normalize(glm::cross(v, any));
  const float turn = draws.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
  const glm::vec3 u = std::cos(turn) * u0 + std::sin(turn) * glm::cross(v, u0);
  const float half = 0.5f * size;
  glm::vec3 center = stalk + v * half;
  const float lowest = center.y - half * (std::fabs(u.y) + std::fabs(v.y));
  if (lowest < 0.05f) center.y += 0.05f - lowest;  // a large leaf low in the crown
  append_mesh(leaves, make_leaf_quad("leaf", center, u * half, v * half, 0));
}

}  // namespace

void add_building(Mesh& into, glm::vec2 at, float half_x, float half_z, float height, float yaw,
                  float tier_height) {
  const glm::mat3 r = yaw_rotation(yaw);
  append_mesh(into, make_box("building", ground(at) + glm::vec3(0.0f, 0.5f * height, 0.0f),
                             glm::vec3(half_x, 0.5f * height, half_z), r));
  if (tier_height <= 0.0f) return;
  const float base = height - 0.1f;
  append_mesh(into, make_box("tier", ground(at) + glm::vec3(0.0f, base + 0.5f * tier_height, 0.0f),
                             glm::vec3(0.6f * half_x, 0.5f * tier_height, 0.6f * half_z), r));
}

void add_tree(Mesh& wood, Mesh& leaves, glm::vec2 at, const TreeShape& t, Draws& draws) {
  const glm::vec3 root = ground(at);
  append_mesh(wood, make_cylinder("trunk", root, kUp, t.trunk_radius, 0.75f * t.trunk_radius,
                                  t.trunk_height, 6));
  const float vertical = 1.2f * t.crown_radius;
  const glm::vec3 crown = root + kUp * (t.trunk_height + 0.8f * vertical);
  // Three limbs from inside the trunk's top, 40° off vertical, into the crown.
  const float phase = draws.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
  for (int k = 0; k < 3; ++k) {
    const float around = phase + 2.0f * std::numbers::pi_v<float> * float(k) / 3.0f;
    const glm::vec3 axis(0.643f * std::cos(around), 0.766f, 0.643f * std::sin(around));
    append_mesh(wood, make_cylinder("limb", root + kUp * (0.9f * t.trunk_height), axis,
                                    0.5f * t.trunk_radius, 0.15f * t.trunk_radius,
                                    0.9f * t.crown_radius, 5));
  }
  for (int i = 0; i < t.leaves; ++i) {
    const glm::vec3 d = random_direction(draws);
    const float shell = draws.uniform(0.6f, 1.0f);
    const glm::vec3 stalk =
        crown + shell * glm::vec3(d.x * t.crown_radius, d.y * vertical, d.z * t.crown_radius);
    add_leaf(leaves, stalk, d, t.leaf_size, draws);
  }
}

void add_street_light(Mesh& into, glm::vec2 at, glm::vec2 facing) {
  const glm::vec2 f = glm::normalize(facing);
  const glm::mat3 along(glm::vec3(f.x, 0.0f, f.y), kUp, glm::vec3(-f.y, 0.0f, f.x));
  const glm::vec3 out(f.x, 0.0f, f.y);
  append_mesh(into, make_cylinder("pole", ground(at), kUp, 0.10f, 0.07f, 8.0f, 8));
  append_mesh(into, make_box("arm", ground(at) + glm::vec3(0.0f, 7.7f, 0.0f) + 0.8f * out,
                             glm::vec3(0.8f, 0.04f, 0.04f), along));
  append_mesh(into, make_box("lamp", ground(at) + glm::vec3(0.0f, 7.62f, 0.0f) + 1.45f * out,
                             glm::vec3(0.3f, 0.06f, 0.13f), along));
}

void add_power_pole(Mesh& into, glm::vec2 at, float height, float yaw) {
  append_mesh(into, make_cylinder("pole", ground(at), kUp, 0.16f, 0.12f, height, 8));
  append_mesh(into, make_box("cross_arm", ground(at) + glm::vec3(0.0f, height - 0.6f, 0.0f),
                             glm::vec3(1.2f, 0.06f, 0.06f), yaw_rotation(yaw)));
}

void add_sign_post(Mesh& into, glm::vec2 at, float height, float yaw) {
  append_mesh(into, make_cylinder("post", ground(at), kUp, 0.035f, 0.035f, height, 6));
  const glm::mat3 r = yaw_rotation(yaw);
  // In front of the post (its radius plus half the plate's thickness).
  const glm::vec3 front = r * glm::vec3(0.0f, 0.0f, 0.05f);
  append_mesh(into, make_box("sign", ground(at) + glm::vec3(0.0f, height - 0.3f, 0.0f) + front,
                             glm::vec3(0.3f, 0.3f, 0.015f), r));
}

void add_bollard(Mesh& into, glm::vec2 at) {
  append_mesh(into, make_cylinder("bollard", ground(at), kUp, 0.1f, 0.1f, 0.9f, 8));
}

}  // namespace sb
