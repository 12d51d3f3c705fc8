#pragma once
// Thin axis-aligned plates over a ground under a square light that faces
// straight down from (0, kLightHeight, 0): scenes whose soft shadows have a
// closed form, shared by the tests of the techniques that must match it.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/scene.h"

namespace sb::test {

constexpr float kLightHeight = 3.0f;

// x ∈ [x0, x1], z ∈ [z0, z1], mid-plane at height h, `half_thickness` thick
// either side of it.
struct Plate {
  float x0, x1, z0, z1, h;
  float half_thickness = 1e-4f;
};

// Exact V at the point (x, y, z) below one plate of no thickness (y = 0:
// the ground): the plate projected from the point onto the light's plane is
// the rectangle scaled by (H − y) / (h − y) about the point, and V = 1 − its
// overlap with the light / the light's area.
double exact_visibility(const Plate& p, double x, double z, double size, double y = 0.0);

// Writes the plates (meshes "plate0", "plate1", ...), any `extra` meshes and
// a ground to dir/plates.glb, seen from `eye` looking at the origin.
std::string write_plates(const std::filesystem::path& dir, const std::vector<Plate>& plates,
                         const glm::vec3& eye, const std::vector<core::Mesh>& extra = {});

// Two plates at different heights whose penumbrae overlap on the ground
// under a light of side kOverlapLightSize, framed from kOverlapEye.
std::vector<Plate> overlapping_plates();
constexpr double kOverlapLightSize = 1.5;
constexpr glm::vec3 kOverlapEye{0.0f, 5.0f, 3.5f};

// A gltf scene entry for that file with a square light of side `size`.
nlohmann::json plate_scene(const std::string& file, double size);

}  // namespace sb::test
