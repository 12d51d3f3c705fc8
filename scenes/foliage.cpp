// foliage — trees from a seeded generator, over a ground plane.
//
// | parameter         | default | meaning                                         |
// |-------------------|---------|-------------------------------------------------|
// | trees             | 4       | trees, on a jittered grid                       |
// | depth             | 3       | branching levels above the trunk                |
// | branches          | 3       | children per branch                             |
// | leaves_per_branch | 10      | leaves along each outermost branch              |
// | leaf_size         | 0.4     | leaf quad side                                  |
// | segments          | 8       | sides of each trunk/branch cylinder             |
// | seed              | 1       | generator seed (same seed, same trees)          |
// | light_size        | 1.0     | side of the square area light                   |
//
// Meshes: "tree_<i>/wood" (closed, one per tree) and "leaves" (all leaves,
// open and alpha-tested), plus the non-casting "ground".
#include "scenes/foliage.h"

#include <cmath>
#include <numbers>

#include "scenes/draws.h"
#include "scenes/leaf.h"
#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"
#include "scenes/triangle_budget.h"

namespace sb {

using core::AlphaMode;
using core::Bounds;
using core::float_param;
using core::int_param;
using core::make_area_light;
using core::Mesh;
using core::Params;
using core::Scene;
using core::SceneType;

namespace {

glm::vec3 any_perpendicular(const glm::vec3& a) {
  const glm::vec3 h = std::fabs(a.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  return glm::normalize(glm::cross(a, h));
}

// `axis` rotated by `angle` about `around` (Rodrigues).
glm::vec3 rotate(const glm::vec3& axis, const glm::vec3& around, float angle) {
  const float c = std::cos(angle), s = std::sin(angle);
  return axis * c + glm::cross(around, axis) * s + around * glm::dot(around, axis) * (1.0f - c);
}

struct Grower {
  const Params& p;
  Draws& rng;
  Mesh& wood;
  Mesh& leaves;
  int segments;

  void branch(glm::vec3 base, glm::vec3 axis, float length, float radius, int depth) {
    const float top = radius * 0.7f;
    append_mesh(wood, make_cylinder("branch", base, axis, radius, top, length, segments));
    const glm::vec3 tip = base + axis * length;
    if (depth == 0) {
      add_leaves(base, axis, length);
      return;
    }
    const int children = p.get_int("branches");
    const float phase = rng.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
    for (int c = 0; c < children; ++c) {
      const float around = phase + 2.0f * std::numbers::pi_v<float> * float(c) / float(children);
      const glm::vec3 side = rotate(any_perpendicular(axis), axis, around);
      const float tilt = rng.uniform(0.45f, 0.8f);
      const glm::vec3 child_axis =
          glm::normalize(rotate(axis, glm::normalize(glm::cross(axis, side)), tilt));
      // Start a little inside the parent's tip so the two closed cylinders
      // overlap instead of sharing vertices.
      const glm::vec3 start = tip - axis * (0.15f * length) * rng.uniform(0.3f, 1.0f);
      branch(start, child_axis, length * rng.uniform(0.62f, 0.75f), top * 0.8f, depth - 1);
    }
  }

  void add_leaves(glm::vec3 base, glm::vec3 axis, float length) {
    const int n = p.get_int("leaves_per_branch");
    const float half = 0.5f * p.get_float("leaf_size");
    for (int i = 0; i < n; ++i) {
      const float along = rng.uniform(0.25f, 1.0f) * length;
      const glm::vec3 out = rotate(any_perpendicular(axis), axis,
                                   rng.uniform(0.0f, 2.0f * std::numbers::pi_v<float>));
      // The stalk at the branch, the blade pointing outwards and a little up.
      const glm::vec3 v = glm::normalize(out + axis * rng.uniform(0.0f, 0.8f));
      const glm::vec3 u = rotate(glm::normalize(glm::cross(v, axis)), v, rng.uniform(-0.6f, 0.6f));
      const glm::vec3 center = base + axis * along + v * half;
      append_mesh(leaves, make_leaf_quad("leaf", center, u * half, v * half, 0));
    }
  }
};

Scene build_foliage(const Params& p) {
  Scene s;
  s.name = "foliage";
  const auto seed = static_cast<uint64_t>(p.get_int("seed"));
  s.textures.push_back(make_leaf_texture(64, static_cast<uint32_t>(seed)));
  // The stream seed·γ + 1 these trees have always been drawn from.
  Draws rng(seed * core::kSplitMix64Gamma + 1);
  Mesh leaves;  // every leaf quad of every tree, with the leaf quads' material
  leaves.name = "leaves";
  leaves.albedo = glm::vec3(1.0f);
  leaves.base_color_texture = 0;
  leaves.alpha_mode = AlphaMode::Mask;
  leaves.alpha_cutoff = 0.5f;
  leaves.double_sided = true;

  const int trees = p.get_int("trees");
  const int per_row = static_cast<int>(std::ceil(std::sqrt(double(trees))));
  const float spacing = 3.2f;
  const float extent = float(per_row - 1) * spacing;
  for (int t = 0; t < trees; ++t) {
    Mesh wood;
    wood.name = "tree_" + std::to_string(t) + "/wood";
    wood.albedo = glm::vec3(0.36f, 0.25f, 0.15f);
    const int row = t / per_row;  // whole rows: the grid cell's row index
    const glm::vec3 root(-0.5f * extent + float(t % per_row) * spacing + rng.uniform(-0.5f, 0.5f),
                         0.0f, -0.5f * extent + float(row) * spacing + rng.uniform(-0.5f, 0.5f));
    const glm::vec3 up =
        glm::normalize(glm::vec3(rng.uniform(-0.08f, 0.08f), 1.0f, rng.uniform(-0.08f, 0.08f)));
    Grower g{p, rng, wood, leaves, p.get_int("segments")};
    g.branch(root, up, rng.uniform(1.5f, 2.1f), 0.13f, p.get_int("depth"));
    s.meshes.push_back(std::move(wood));
  }
  if (!leaves.indices.empty()) s.meshes.push_back(std::move(leaves));

  Mesh ground = make_ground_plane("ground", glm::vec3(0), 4.0f * (extent + spacing) + 20.0f);
  ground.albedo = glm::vec3(0.75f, 0.72f, 0.62f);
  s.meshes.push_back(std::move(ground));

  const Bounds b = s.caster_bounds();
  const float r = b.radius();
  const glm::vec3 c = b.center();
  s.light = make_area_light(
      glm::vec3(c.x, 0.0f, c.z) + glm::vec3(0.35f, 1.0f, 0.25f) * (3.0f * r + 6.0f),
      glm::vec3(c.x, 0.0f, c.z), p.get_float("light_size"), p.get_float("light_size"));
  s.camera.eye = glm::vec3(c.x, 0.0f, c.z) + glm::vec3(0.0f, 1.1f * r + 2.0f, 2.0f * r + 3.0f);
  s.camera.target = glm::vec3(c.x, 0.35f * b.hi.y, c.z);
  s.camera.fov_y_degrees = 50.0f;
  s.camera.far_plane = 20.0f * (r + 10.0f);
  return s;
}

}  // namespace

// Per tree: sum_{d<=depth} branches^d cylinders of at most 4*segments
// triangles, and branches^depth outermost branches with two triangles a leaf.
std::pair<std::string, std::string> check_foliage(const Params& p) {
  const uint64_t b = uint64_t(p.get_int("branches"));
  uint64_t cylinders = 0, outermost = 1;
  for (int d = 0; d <= p.get_int("depth"); ++d) {
    if (d > 0) outermost = budget_mul(outermost, b);
    cylinders += outermost;
  }
  const uint64_t per_tree = budget_mul(cylinders, 4 * uint64_t(p.get_int("segments"))) +
                            budget_mul(outermost, 2 * uint64_t(p.get_int("leaves_per_branch")));
  return triangle_budget(budget_mul(per_tree, uint64_t(p.get_int("trees"))), "trees");
}

SceneType foliage_scene_type() {
  return {"foliage",
          "seeded trees: closed tapered-cylinder wood, alpha-tested double-sided leaf quads",
          {int_param("trees", 4, 1, 256, "trees, on a jittered grid"),
           int_param("depth", 3, 0, 6, "branching levels above the trunk"),
           int_param("branches", 3, 1, 6, "children per branch"),
           int_param("leaves_per_branch", 10, 0, 64, "leaves along each outermost branch"),
           float_param("leaf_size", 0.4, 0.01, 10.0, "leaf quad side"),
           int_param("segments", 8, 3, 64, "sides of each trunk/branch cylinder"),
           int_param("seed", 1, 0, 2147483647, "generator seed"),
           float_param("light_size", 1.0, 0.0, 1e4, "side of the square area light")},
          build_foliage,
          check_foliage};
}

}  // namespace sb
