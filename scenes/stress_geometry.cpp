// stress_geometry — geometry that breaks techniques, one case per variant,
// each a caster at `height` over a ground plane (y = 0) under a square area
// light `light_height` above the origin, facing straight down; the camera
// looks down at 50° from the +z side at the caster's shadow.
//
// | parameter    | default  | meaning                                                   |
// |--------------|----------|-----------------------------------------------------------|
// | case         | "sliver" | sliver, degenerate, coincident or thin (below)            |
// | segments     | 2048     | sliver: sides of the disc (its triangles' aspect ratio)   |
// | width        | 0.002    | thin: side of the rods' square cross-section              |
// | height       | 1.0      | of the caster's centre above the ground                   |
// | light_size   | 1.0      | side of the square area light                             |
// | light_height | 6.0      | of the light above the ground (> height + 0.5)            |
//
// sliver. A closed disc of radius 1 and thickness 0.05 with `segments`
// sides: its caps are fans of triangles 1 long and 2π/segments wide (aspect
// ratio ~326 at 2048), its rim quads as thin. Shadow volumes extrude
// every rim edge; maps rasterise sub-pixel triangles.
//
// degenerate. A closed box 1.6 × 0.1 × 1.6 whose top face carries extra
// zero-area triangles: each of its two triangles is split at a point on its
// long edge, and a triangle with two identical vertices is added per edge of
// the top face. The box is no longer closed by the topology check
// (a repeated vertex makes an edge used three times): techniques that need
// closed casters skip it with that reason, the rest must ignore the
// zero-area triangles.
//
// coincident. Two identical closed boxes 1.2 × 0.1 × 1.2 at the same place
// (z-fighting casters, each closed), over two coincident ground planes
// (z-fighting receivers).
//
// thin. Three closed rods 3 long with a `width` × `width` cross-section,
// side by side along x at `height`: at the default, a 2048² map over them
// spans ~1.5e-3 per texel, so a rod covers about one texel of it.
#include "scenes/stress_geometry.h"

#include <cmath>
#include <string>
#include <utility>

#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"

namespace sb {

using core::choice_param;
using core::float_param;
using core::int_param;
using core::make_area_light;
using core::Mesh;
using core::Params;
using core::Scene;
using core::SceneType;

namespace {

const glm::vec3 kCasterAlbedo(0.55f, 0.5f, 0.45f);

Mesh caster(Mesh m) {
  m.albedo = kCasterAlbedo;
  return m;
}

// A closed disc: two fans and a rim of quads, counter-clockwise outward.
Mesh sliver_disc(float y, int segments) {
  Mesh m = make_cylinder("disc", glm::vec3(0.0f, y - 0.025f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f),
                         1.0f, 1.0f, 0.05f, segments);
  return caster(std::move(m));
}

// The box with zero-area triangles on its top face (+y).
Mesh degenerate_box(float y) {
  Mesh m = caster(make_box("box", glm::vec3(0.0f, y, 0.0f), glm::vec3(0.8f, 0.05f, 0.8f)));
  const size_t triangles = m.indices.size() / 3;
  std::vector<uint32_t> extra;
  for (size_t t = 0; t < triangles; ++t) {
    const uint32_t a = m.indices[3 * t], b = m.indices[3 * t + 1], c = m.indices[3 * t + 2];
    const bool top = m.positions[a].y > y && m.positions[b].y > y && m.positions[c].y > y;
    if (!top) continue;
    // A collinear triangle on each edge (its middle vertex at the edge's
    // midpoint) and one with a repeated vertex.
    for (const auto& [p, q] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
      const auto mid = uint32_t(m.positions.size());
      m.positions.push_back(0.5f * (m.positions[p] + m.positions[q]));
      m.normals.push_back(m.normals[p]);
      if (!m.uvs.empty()) m.uvs.push_back(0.5f * (m.uvs[p] + m.uvs[q]));
      extra.insert(extra.end(), {p, mid, q});
      extra.insert(extra.end(), {p, p, q});
    }
  }
  m.indices.insert(m.indices.end(), extra.begin(), extra.end());
  return m;
}

void build(Scene& s, const Params& p) {
  const std::string c = p.get_string("case");
  const float height = p.get_float("height");
  const float light_height = p.get_float("light_height");
  const float light_size = p.get_float("light_size");
  if (c == "sliver") {
    s.meshes.push_back(sliver_disc(height, p.get_int("segments")));
  } else if (c == "degenerate") {
    s.meshes.push_back(degenerate_box(height));
  } else if (c == "coincident") {
    for (const char* name : {"box_a", "box_b"})
      s.meshes.push_back(
          caster(make_box(name, glm::vec3(0.0f, height, 0.0f), glm::vec3(0.6f, 0.05f, 0.6f))));
  } else {  // thin
    const float w = p.get_float("width");
    for (int i = -1; i <= 1; ++i)
      s.meshes.push_back(
          caster(make_box("rod_" + std::to_string(i + 1), glm::vec3(0.5f * float(i), height, 0.0f),
                          glm::vec3(0.5f * w, 0.5f * w, 1.5f))));
  }
  for (const char* name : c == "coincident" ? std::vector<const char*>{"ground", "ground_twin"}
                                            : std::vector<const char*>{"ground"}) {
    Mesh ground = make_ground_plane(name, glm::vec3(0.0f), 12.0f);
    ground.albedo = glm::vec3(0.8f, 0.78f, 0.74f);
    s.meshes.push_back(std::move(ground));
  }
  s.light =
      make_area_light(glm::vec3(0.0f, light_height, 0.0f), glm::vec3(0.0f), light_size, light_size);
  s.camera.fov_y_degrees = 45.0f;
  s.camera.target = glm::vec3(0.0f, 0.0f, 0.0f);
  const float distance = 5.0f;
  s.camera.eye = glm::vec3(0.0f, distance * std::sin(glm::radians(50.0f)),
                           distance * std::cos(glm::radians(50.0f)));
  s.camera.near_plane = 0.05f;
  s.camera.far_plane = 40.0f;
}

Scene build_stress_geometry(const Params& p) {
  Scene s;
  s.name = "stress_geometry";
  build(s, p);
  return s;
}

std::pair<std::string, std::string> check_stress_geometry(const Params& p) {
  if (p.get_float("light_height") <= p.get_float("height") + 0.5f)
    return {"light_height", "expected a light above the caster: light_height > height + 0.5"};
  return {"", ""};
}

}  // namespace

SceneType stress_geometry_scene_type() {
  return {"stress_geometry",
          "geometry that breaks techniques: sliver or degenerate triangles, coincident "
          "(z-fighting) surfaces, or occluders thinner than a map texel (docs/stability.md)",
          {choice_param("case", "sliver", {"sliver", "degenerate", "coincident", "thin"},
                        "sliver disc, zero-area triangles, coincident boxes and grounds, or "
                        "one-texel rods"),
           int_param("segments", 2048, 3, 65536, "sliver: sides of the disc"),
           float_param("width", 0.002, 1e-6, 1.0, "thin: side of the rods' cross-section"),
           float_param("height", 1.0, 0.05, 1000.0, "height of the caster's centre"),
           float_param("light_size", 1.0, 0.0, 1e4, "side of the square area light"),
           float_param("light_height", 6.0, 0.1, 1e5, "height of the light above the ground")},
          build_stress_geometry,
          check_stress_geometry};
}

}  // namespace sb
