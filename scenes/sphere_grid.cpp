#include "scenes/sphere_grid.h"

#include <cmath>
#include <cstdint>
#include <numbers>

#include "scenes/triangle_budget.h"

namespace sb {

using core::AnalyticShape;
using core::bool_param;
using core::float_param;
using core::int_param;
using core::make_area_light;
using core::Mesh;
using core::Params;
using core::Scene;
using core::SceneType;

Mesh make_uv_sphere(const std::string& name, glm::vec3 center, float radius, int slices,
                    int stacks) {
  Mesh m;
  m.name = name;
  // One vertex per pole and one ring per inner stack, the seam shared: the
  // mesh is closed without welding.
  m.positions.push_back(center + glm::vec3(0, radius, 0));
  m.normals.emplace_back(0, 1, 0);
  for (int i = 1; i < stacks; ++i) {
    const float theta = std::numbers::pi_v<float> * float(i) / float(stacks);
    for (int j = 0; j < slices; ++j) {
      const float phi = 2.0f * std::numbers::pi_v<float> * float(j) / float(slices);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                        -std::sin(theta) * std::sin(phi));
      m.positions.push_back(center + radius * n);
      m.normals.push_back(n);
    }
  }
  m.positions.push_back(center - glm::vec3(0, radius, 0));
  m.normals.emplace_back(0, -1, 0);
  const auto ring = [&](int i, int j) { return uint32_t(1 + (i - 1) * slices + (j % slices)); };
  const uint32_t south = uint32_t(m.positions.size() - 1);
  for (int j = 0; j < slices; ++j) {  // north cap, counter-clockwise seen from outside
    m.indices.insert(m.indices.end(), {0u, ring(1, j), ring(1, j + 1)});
  }
  for (int i = 1; i < stacks - 1; ++i)
    for (int j = 0; j < slices; ++j) {
      const uint32_t a = ring(i, j), b = ring(i, j + 1), c = ring(i + 1, j), d = ring(i + 1, j + 1);
      m.indices.insert(m.indices.end(), {a, c, d, a, d, b});
    }
  for (int j = 0; j < slices; ++j)
    m.indices.insert(m.indices.end(), {south, ring(stacks - 1, j + 1), ring(stacks - 1, j)});
  return m;
}

Mesh make_ground_plane(const std::string& name, glm::vec3 center, float half_size) {
  Mesh m;
  m.name = name;
  const float h = half_size;
  m.positions = {center + glm::vec3(-h, 0, -h), center + glm::vec3(-h, 0, h),
                 center + glm::vec3(h, 0, h), center + glm::vec3(h, 0, -h)};
  m.normals.assign(4, glm::vec3(0, 1, 0));
  m.indices = {0, 1, 2, 0, 2, 3};
  m.casts_shadow = false;  // a receiver under everything never occludes the light
  return m;
}

namespace {

Scene build_sphere_grid(const Params& p) {
  const int grid = p.get_int("grid");
  const int layers = p.get_int("layers");
  const float radius = p.get_float("radius");
  const float spacing = p.get_float("spacing");
  const float height = p.get_float("height");
  const int slices = p.get_int("slices");
  const int stacks = p.get_int("stacks");
  const bool analytic = p.get_bool("analytic");

  Scene s;
  s.name = "sphere_grid";
  const float extent = float(grid - 1) * spacing;
  for (int layer = 0; layer < layers; ++layer)
    for (int row = 0; row < grid; ++row)
      for (int col = 0; col < grid; ++col) {
        const glm::vec3 c(-0.5f * extent + float(col) * spacing, height + float(layer) * spacing,
                          -0.5f * extent + float(row) * spacing);
        Mesh sphere = make_uv_sphere("sphere_" + std::to_string(layer) + "_" + std::to_string(row) +
                                         "_" + std::to_string(col),
                                     c, radius, slices, stacks);
        sphere.albedo = glm::vec3(0.85f, 0.32f, 0.25f);
        if (analytic) sphere.analytic = AnalyticShape::sphere(c, radius);
        s.meshes.push_back(std::move(sphere));
      }
  Mesh ground = make_ground_plane("ground", glm::vec3(0), 4.0f * (extent + spacing) + 20.0f);
  ground.albedo = glm::vec3(0.8f);
  s.meshes.push_back(std::move(ground));

  const float size = p.get_float("light_size");
  const float light_height = p.get_float("light_height");
  s.light =
      make_area_light(glm::vec3(0.35f, 1.0f, 0.25f) * light_height, glm::vec3(0.0f), size, size);
  const float view = 0.5f * extent + spacing;
  s.camera.eye = glm::vec3(0.0f, 1.35f * view + 2.0f, 1.6f * view + 2.5f);
  s.camera.target = glm::vec3(0.0f, 0.0f, 0.25f * view);
  s.camera.fov_y_degrees = 50.0f;
  s.camera.near_plane = 0.1f;
  s.camera.far_plane = 10.0f * (view + light_height);
  return s;
}

}  // namespace

// 2*slices*(stacks-1) per sphere, grid² spheres per layer, and the ground.
std::pair<std::string, std::string> check_sphere_grid(const Params& p) {
  const uint64_t grid = uint64_t(p.get_int("grid"));
  const uint64_t per_sphere = 2 * uint64_t(p.get_int("slices")) * uint64_t(p.get_int("stacks") - 1);
  return triangle_budget(
      budget_mul(budget_mul(grid * grid, uint64_t(p.get_int("layers"))), per_sphere), "grid");
}

SceneType sphere_grid_scene_type() {
  return {"sphere_grid",
          "grid×grid UV spheres (× layers) over a ground plane, square area light "
          "(Forest et al. 2006)",
          {int_param("grid", 9, 1, 256, "spheres per row and column"),
           int_param("layers", 1, 1, 64, "stacked grids"),
           int_param("slices", 20, 3, 1024, "sphere longitude segments"),
           int_param("stacks", 20, 2, 1024,
                     "sphere latitude segments; triangles = 2*slices*(stacks-1)"),
           float_param("radius", 0.5, 1e-3, 1e3, "sphere radius"),
           float_param("spacing", 1.5, 1e-3, 1e4, "centre distance between neighbours"),
           float_param("height", 1.2, 0.0, 1e4, "height of the first layer's centres"),
           float_param("light_size", 2.0, 0.0, 1e4, "side of the square area light"),
           float_param("light_height", 10.0, 1e-2, 1e5,
                       "distance scale of the light (placed at light_height*(0.35,1,0.25))"),
           bool_param("analytic", false,
                      "the reference occludes with the exact spheres, not their triangles "
                      "(the G-buffer and the techniques keep the triangles)")},
          build_sphere_grid,
          check_sphere_grid};
}

}  // namespace sb
