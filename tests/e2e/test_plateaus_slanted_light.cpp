// plateaus under a light whose rectangle the ground sees as a parallelogram:
// the light hangs over a square plate but faces a point 50° off the
// vertical, and is turned 45° about its own axis (a glTF spot light's node
// rotation), so its axes projected on the ground meet at 114°. The outer
// penumbra's width across each side of the plate's shadow is the support
// function of that parallelogram, against the exact reference's shadow.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "../gltf/gltf_builder.h"
#include "core/scene_types.h"
#include "e2e_util.h"
#include "scenes/gltf_export.h"
#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"

namespace sb::test {

using core::ImageF;
using core::make_area_light;
using core::Scene;

namespace {

using json = nlohmann::json;

constexpr float kLight = 5.0f;   // the light's centre: (0, kLight, 0)
constexpr float kPlate = 1.5f;   // the plate's height
constexpr float kHalf = 0.5f;    // the plate's half side, along x and z
constexpr float kSize = 1.5f;    // the light's side
constexpr float kSlant = 50.0f;  // the light's normal from the vertical, degrees
constexpr float kTurn = 45.0f;   // the light's turn about its normal, degrees

std::string write_slanted_light_scene(const std::filesystem::path& dir) {
  Scene s;
  s.meshes.push_back(make_ground_plane("ground", {0.0f, 0.0f, 0.0f}, 20.0f));
  s.meshes.push_back(make_box("plate", {0.0f, kPlate, 0.0f}, {kHalf, 1e-3f, kHalf}));
  const glm::vec3 target{kLight * std::tan(glm::radians(kSlant)), 0.0f, 0.0f};
  s.light = make_area_light({0.0f, kLight, 0.0f}, target, kSize, kSize, 1.0f);
  // Turn the rectangle about its normal; the export writes the turned axes
  // as the light node's rotation.
  const float c = std::cos(glm::radians(kTurn)), sn = std::sin(glm::radians(kTurn));
  const glm::vec3 u = s.light.half_u, v = s.light.half_v;
  s.light.half_u = c * u + sn * v;
  s.light.half_v = -sn * u + c * v;
  // From straight above (the plate hides only the ground under itself).
  s.camera.eye = {0.0f, 9.0f, 0.0f};
  s.camera.target = {0.0f, 0.0f, 0.0f};
  s.camera.up = {0.0f, 0.0f, -1.0f};
  s.camera.fov_y_degrees = 30.0f;
  const auto file = dir / "slanted_light.glb";
  export_glb(s, file.string());
  return file.string();
}

// The extent along x of the ground pixels with V < 1 − 1e-3 in the strip
// |z| < 0.05 (or, with `along_z`, the extent along z where |x| < 0.05).
double shadow_width(const ImageF& positions, const ImageF& v, bool along_z) {
  double lo = 1e9, hi = -1e9;
  for (size_t i = 0; i < v.pixel_count(); ++i) {
    const float* p = &positions.data[i * 4];
    if (p[3] == 0.0f || std::abs(p[1]) > 1e-4f) continue;
    const float across = along_z ? p[0] : p[2], along = along_z ? p[2] : p[0];
    if (std::abs(across) > 0.05f || v.data[i] >= 1.0f - 1e-3f) continue;
    lo = std::min(lo, double(along));
    hi = std::max(hi, double(along));
  }
  return hi - lo;
}

// Measured (240², exact reference) with the 2×2 solve: widths 1.99 across x
// and 2.31 across z, the reference's 2.01 and 2.27; with a rectangle's
// coordinates (dot products with each axis) plateaus gave 2.39 and 2.07.
// Each axis's outer penumbra (the width beyond the hard shadow's 1.43) must
// be within 15% of the reference's.
TEST(PlateausSlantedLight, OuterPenumbraIsTheProjectedParallelogramsSupport) {
  TempDir dir;
  const json scene = {{"type", "gltf"},
                      {"params", {{"file", write_slanted_light_scene(dir.path)}}}};
  const json config = {{"name", "plateaus_slanted"},
                       {"scenes", json::array({scene})},
                       {"techniques", json::array({"plateaus"})},
                       {"resolutions", json::array({json::array({240, 240})})},
                       {"frames", {{"warmup", 0}, {"timed", 1}}},
                       {"reference", {{"method", "exact"}}}};
  const auto out = run_config(config, "plateaus_slanted_light", gl::Backend::OSMesa, true,
                              /*write_gbuffer=*/true);
  ASSERT_EQ(out.summary.ok, 1) << out.records.at(0).value("reason", "");
  ASSERT_EQ(out.records.at(0)["reference"]["method"], "exact_clipper");
  const ImageF positions = out.gbuffer_positions();
  const ImageF plateaus = out.visibility("plateaus");
  const ImageF ref = out.reference_visibility();
  const double hard = 2.0 * kHalf * kLight / (kLight - kPlate);
  for (const bool along_z : {false, true}) {
    SCOPED_TRACE(along_z ? "across z" : "across x");
    const double truth = shadow_width(positions, ref, along_z);
    const double width = shadow_width(positions, plateaus, along_z);
    std::printf("%s: plateaus %.3f, reference %.3f, hard shadow %.3f\n", along_z ? "z" : "x", width,
                truth, hard);
    ASSERT_GT(truth, hard + 0.3);
    EXPECT_NEAR(width, truth, 0.15 * (truth - hard));
  }
}

}  // namespace
}  // namespace sb::test
