// standing — an occluder standing on the ground, whose shadow runs from a
// hard contact line at its foot to a wide penumbra at its far end: the case
// that shows a fixed-width blur's failure (the same softness at both ends).
//
// | parameter    | default | meaning                                                  |
// |--------------|---------|----------------------------------------------------------|
// | height       | 2.0     | of the box, standing on y = 0                            |
// | width        | 0.4     | side of its square footprint (0.1: a pole; 0.5: a        |
// |              |         | character-sized block with height 1.8)                   |
// | light_size   | 1.0     | side of the square area light                            |
// | light_height | 6.0     | height of the light; must exceed `height`                |
// | light_offset | 3.0     | horizontal distance from the box's axis to the light's   |
// |              |         | centre, along −x                                         |
//
// The box ("occluder") spans x, z ∈ [−width/2, width/2], y ∈ [0, height]. The
// light faces straight down from (−light_offset, light_height, 0), so the
// shadow falls along +x: from the foot at x = width/2 to the tip, the shadow
// of the far top edge from the light's centre,
//   tip = −light_offset + (light_offset + width/2) · light_height / (light_height − height),
// where the penumbra is light_size · height / (light_height − height) wide
// (0.5 at the defaults, tip = 1.8). The camera looks along −z, 50° down, at
// the middle of the shadow, framing the box's foot and the tip's penumbra.
#include "scenes/standing.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>

#include "core/error.h"
#include "scenes/mesh_builders.h"
#include "scenes/sphere_grid.h"

namespace sb {

using core::float_param;
using core::InputError;
using core::make_area_light;
using core::Mesh;
using core::Params;
using core::Scene;
using core::SceneType;

namespace {

constexpr float kStandingFovY = 45.0f;  // degrees, vertical
constexpr float kElevation = 50.0f;     // camera, degrees below the horizon
constexpr float kFrameMargin = 1.3f;    // framed half-width over the shadow's half-length

struct StandingSetup {
  float height, width, light_size, light_height, light_offset;
};

StandingSetup read_standing_setup(const Params& p) {
  return {p.get_float("height"), p.get_float("width"), p.get_float("light_size"),
          p.get_float("light_height"), p.get_float("light_offset")};
}

std::pair<std::string, std::string> check_standing(const Params& p) {
  const StandingSetup d = read_standing_setup(p);
  if (!(d.light_height > d.height)) {
    std::ostringstream s;
    s << "expected a number greater than the box's height (" << d.height << "), found "
      << d.light_height;
    return {"light_height", s.str()};
  }
  return {};
}

Scene build_standing(const Params& p) {
  if (const auto [param, problem] = check_standing(p); !problem.empty())
    throw InputError("", "/params/" + param, problem);
  const StandingSetup d = read_standing_setup(p);
  Scene s;
  s.name = "standing";
  const float half = 0.5f * d.width;
  Mesh box = make_box("occluder", glm::vec3(0.0f, 0.5f * d.height, 0.0f),
                      glm::vec3(half, 0.5f * d.height, half));
  box.albedo = glm::vec3(0.55f, 0.45f, 0.40f);
  s.meshes.push_back(std::move(box));
  s.light = make_area_light(glm::vec3(-d.light_offset, d.light_height, 0.0f),
                            glm::vec3(-d.light_offset, 0.0f, 0.0f), d.light_size, d.light_size);

  // The shadow from the foot to beyond the tip's penumbra, framed across the
  // image's width (4:3) at its centre.
  const float tip =
      -d.light_offset + (d.light_offset + half) * d.light_height / (d.light_height - d.height);
  const float penumbra = d.light_size * d.height / (d.light_height - d.height);
  const float from = -half, to = tip + penumbra;
  const glm::vec3 center(0.5f * (from + to), 0.0f, 0.0f);
  const float half_width = kFrameMargin * 0.5f * (to - from);
  const float tan_x = std::tan(glm::radians(0.5f * kStandingFovY)) * 4.0f / 3.0f;
  const float distance = std::max(half_width / tan_x, 1.5f * d.height);
  const float elevation = glm::radians(kElevation);
  s.camera.fov_y_degrees = kStandingFovY;
  s.camera.target = center;
  s.camera.eye = center + distance * glm::vec3(0.0f, std::sin(elevation), std::cos(elevation));
  s.camera.near_plane = 0.01f * distance;
  s.camera.far_plane = 20.0f * distance;

  // Every downward ray of a frame up to 2:1 meets this ground before the far plane.
  Mesh ground = make_ground_plane("ground", center, 10.0f * distance);
  ground.albedo = glm::vec3(0.8f, 0.78f, 0.74f);
  s.meshes.push_back(std::move(ground));
  return s;
}

}  // namespace

SceneType standing_scene_type() {
  return {"standing",
          "a box standing on the ground under a light to one side: a shadow hard at the contact "
          "line and widest at its far end",
          {float_param("height", 2.0, 1e-3, 1e4, "height of the box, standing on the ground"),
           float_param("width", 0.4, 1e-4, 1e4, "side of the box's square footprint"),
           float_param("light_size", 1.0, 0.0, 1e4, "side of the square area light"),
           float_param("light_height", 6.0, 1e-2, 1e5, "height of the light (above the box)"),
           float_param("light_offset", 3.0, 0.0, 1e4,
                       "horizontal distance from the box to the light's centre, along -x")},
          build_standing,
          check_standing};
}

}  // namespace sb
