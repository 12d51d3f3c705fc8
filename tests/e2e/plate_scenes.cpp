#include "plate_scenes.h"

#include <algorithm>

#include "scenes/gltf_export.h"
#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"

namespace sb::test {

using core::Mesh;
using core::Scene;

double exact_visibility(const Plate& p, double x, double z, double size, double y) {
  const double k = (kLightHeight - y) / (p.h - y), half = 0.5 * size;
  const auto overlap = [&](double lo, double hi, double at) {
    const double a = at + (lo - at) * k, b = at + (hi - at) * k;
    return std::max(0.0, std::min(b, half) - std::max(a, -half));
  };
  return 1.0 - overlap(p.x0, p.x1, x) * overlap(p.z0, p.z1, z) / (size * size);
}

std::string write_plates(const std::filesystem::path& dir, const std::vector<Plate>& plates,
                         const glm::vec3& eye, const std::vector<Mesh>& extra) {
  Scene s;
  s.meshes.push_back(make_ground_plane("ground", {0.0f, 0.0f, 0.0f}, 20.0f));
  for (size_t i = 0; i < plates.size(); ++i) {
    const Plate& p = plates[i];
    s.meshes.push_back(make_box("plate" + std::to_string(i),
                                {0.5f * (p.x0 + p.x1), p.h, 0.5f * (p.z0 + p.z1)},
                                {0.5f * (p.x1 - p.x0), p.half_thickness, 0.5f * (p.z1 - p.z0)}));
  }
  for (const Mesh& m : extra) s.meshes.push_back(m);
  s.light.center = {0.0f, kLightHeight, 0.0f};
  s.light.target = {0.0f, 0.0f, 0.0f};
  s.camera.eye = eye;
  s.camera.target = {0.0f, 0.0f, 0.0f};
  const auto file = dir / "plates.glb";
  export_glb(s, file.string());
  return file.string();
}

std::vector<Plate> overlapping_plates() {
  return {{-1.2f, 0.1f, -0.8f, 0.8f, 1.0f}, {-0.1f, 0.9f, -0.7f, 0.7f, 1.6f}};
}

nlohmann::json plate_scene(const std::string& file, double size) {
  return {{"type", "gltf"},
          {"params", {{"file", file}}},
          {"light", {{"center", {0.0, kLightHeight, 0.0}}, {"target", {0, 0, 0}}, {"size", size}}}};
}

}  // namespace sb::test
